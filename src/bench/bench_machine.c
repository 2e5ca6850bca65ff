/* The machine's limits, measured roughly with simple loops:
 *   clock      a chain of dependent integer multiplications (3 cycles each on x86-64);
 *   FMA        independent chains of vector fused multiply-adds, as many as
 *              hide the latency: the floating-point peak one core reaches;
 *   bandwidth  STREAM-like loops over arrays much larger than the caches:
 *              triad a[i] = b[i] + s c[i] (3 x 4 bytes per element, the
 *              write-allocate read not counted) and a read-only sum.
 * Each figure is the best of a few runs, with 1 thread and with all cores. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#ifdef _OPENMP
#include <omp.h>
#endif
#if defined(__AVX512F__) || defined(__AVX2__)
#include <immintrin.h>
#endif

#include "bench.h"
#include "../io/io_json.h"

static double cpuinfo_mhz(void)
{
    FILE *f = fopen("/proc/cpuinfo", "r");
    if (!f) return 0;
    char line[512];
    double mhz = 0;
    while (fgets(line, sizeof line, f))
        if (strncmp(line, "cpu MHz", 7) == 0) {
            const char *c = strchr(line, ':');
            if (c) mhz = atof(c + 1);
            break;
        }
    fclose(f);
    return mhz;
}

static double clock_runs(long iters, int reps)
{
#if defined(__x86_64__)
    /* A chain of 10 dependent multiplications an iteration, 3 cycles each on
     * every x86-64 core since 2011 (Intel and AMD alike). Not a chain of
     * adds of a constant: newer cores fold those in the renamer, several a
     * cycle (an Intel Xeon read 21 GHz that way). */
    double best = 0;
    for (int rep = 0; rep < reps; rep++) {
        uint64_t x = 3, one = 1;
        double t0 = sph_now_ms();
        for (long i = 0; i < iters; i++)
            __asm__ volatile("imul %1, %0\n\timul %1, %0\n\timul %1, %0\n\timul %1, %0\n\timul %1, %0\n\t"
                             "imul %1, %0\n\timul %1, %0\n\timul %1, %0\n\timul %1, %0\n\timul %1, %0\n\t"
                             : "+r"(x)
                             : "r"(one));
        double ms = sph_now_ms() - t0;
        if (x != 3) return 0;
        if (ms > 0) best = fmax(best, (double)iters * 30 / (ms * 1e6));
    }
    return best;
#else
    (void)iters;
    (void)reps;
    return 0;
#endif
}

/* many short runs (about 5 ms each), the fastest kept: a run that another
 * process interrupts only comes out slower */
static double measure_clock_ghz(bool quick) { return clock_runs(700000, quick ? 10 : 40); }

double bench_clock_probe(void) { return clock_runs(350000, 6); }

static int vector_lanes(void)
{
#if defined(__AVX512F__)
    return 16;
#elif defined(__AVX2__)
    return 8;
#else
    return 1;
#endif
}

/* Floating-point operations done by one thread in `iters` rounds of 12
 * independent FMA chains (12 named registers: an array would live in memory). */
#define FMA12(F) F(0) F(1) F(2) F(3) F(4) F(5) F(6) F(7) F(8) F(9) F(10) F(11)
static double fma_rounds(long iters, float *sink)
{
#if defined(__AVX512F__)
#define DECL(k) __m512 acc##k = _mm512_set1_ps(1.0f + (float)(k) * 1e-3f);
#define STEP(k) acc##k = _mm512_fmadd_ps(acc##k, a, b);
#define SUM(k) s += _mm512_reduce_add_ps(acc##k);
    FMA12(DECL)
    const __m512 a = _mm512_set1_ps(0.9999999f), b = _mm512_set1_ps(1e-7f);
    for (long i = 0; i < iters; i++) {
        FMA12(STEP)
    }
    float s = 0;
    FMA12(SUM)
    *sink = s;
    return (double)iters * 12 * 16 * 2;
#undef DECL
#undef STEP
#undef SUM
#elif defined(__AVX2__) && defined(__FMA__)
#define DECL(k) __m256 acc##k = _mm256_set1_ps(1.0f + (float)(k) * 1e-3f);
#define STEP(k) acc##k = _mm256_fmadd_ps(acc##k, a, b);
#define SUM(k) _mm256_storeu_ps(out, acc##k); for (int l = 0; l < 8; l++) s += out[l];
    FMA12(DECL)
    const __m256 a = _mm256_set1_ps(0.9999999f), b = _mm256_set1_ps(1e-7f);
    for (long i = 0; i < iters; i++) {
        FMA12(STEP)
    }
    float out[8], s = 0;
    FMA12(SUM)
    *sink = s;
    return (double)iters * 12 * 8 * 2;
#undef DECL
#undef STEP
#undef SUM
#else
    float acc[12];
    for (int k = 0; k < 12; k++) acc[k] = 1.0f + (float)k * 1e-3f;
    for (long i = 0; i < iters; i++)
#if defined(__FMA__) || defined(__ARM_FEATURE_FMA) || defined(FP_FAST_FMAF)
        for (int k = 0; k < 12; k++) acc[k] = fmaf(acc[k], 0.9999999f, 1e-7f);
#else /* fmaf is a library routine without the instruction (0.8 GFLOP/s on a Xeon, where the passes multiply and
       * add at some 10 a core): the passes' own operations, a multiply and an add */
        for (int k = 0; k < 12; k++) acc[k] = acc[k] * 0.9999999f + 1e-7f;
#endif
    float s = 0;
    for (int k = 0; k < 12; k++) s += acc[k];
    *sink = s;
    return (double)iters * 12 * 2;
#endif
}

static double measure_fma(int threads, bool quick)
{
    const long iters = 200000; /* about 2 ms per run; the fastest of many kept */
    double best = 0;
    for (int rep = 0; rep < (quick ? 10 : 60); rep++) {
        double flops = 0;
        float sink = 0;
        double t0 = sph_now_ms();
#pragma omp parallel num_threads(threads) reduction(+ : flops, sink)
        {
            float s = 0;
            flops += fma_rounds(iters, &s);
            sink += s;
        }
        double ms = sph_now_ms() - t0;
        if (sink == 12345.678f) fputc(' ', stderr); /* keep the result alive */
        if (ms > 0) best = fmax(best, flops / (ms * 1e6));
    }
    return best;
}

/* Sum of 64 floats, with vector loads where the build has them. */
static inline float sum64(const float *a)
{
#if defined(__AVX512F__)
    __m512 s = _mm512_add_ps(_mm512_add_ps(_mm512_loadu_ps(a), _mm512_loadu_ps(a + 16)),
                             _mm512_add_ps(_mm512_loadu_ps(a + 32), _mm512_loadu_ps(a + 48)));
    return _mm512_reduce_add_ps(s);
#else
    float p[16] = {0};
    for (int j = 0; j < 64; j += 16)
        for (int l = 0; l < 16; l++) p[l] += a[j + l];
    float s = 0;
    for (int l = 0; l < 16; l++) s += p[l];
    return s;
#endif
}

static void measure_stream(bench_machine *m, bool quick)
{
    const size_t n = quick ? (size_t)8 << 20 : (size_t)16 << 20; /* floats per array: 32 or 64 MB */
    float *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b), *c = malloc(n * sizeof *c);
    m->array_mb = (double)(n * sizeof(float)) / (1 << 20);
    if (!a || !b || !c) goto out;
    const int cores = m->cores;
    /* first touch by the threads that stream them (static schedule, as below) */
#pragma omp parallel for schedule(static) num_threads(cores)
    for (int64_t i = 0; i < (int64_t)n; i++) {
        a[i] = 0.0f;
        b[i] = 1.0f;
        c[i] = 2.0f;
    }
    for (int t = 0; t < 2; t++) {
        int threads = t ? cores : 1;
        double best_triad = 0, best_read = 0;
        for (int rep = 0; rep < (quick ? 4 : 12); rep++) {
            double t0 = sph_now_ms();
#pragma omp parallel for schedule(static) num_threads(threads)
            for (int64_t i = 0; i < (int64_t)n; i++) a[i] = b[i] + 0.5f * c[i];
            double ms = sph_now_ms() - t0;
            if (ms > 0) best_triad = fmax(best_triad, 3.0 * sizeof(float) * (double)n / (ms * 1e6));
            float sum = 0;
            t0 = sph_now_ms();
#pragma omp parallel for schedule(static) num_threads(threads) reduction(+ : sum)
            for (int64_t blk = 0; blk < (int64_t)(n / 64); blk++) sum += sum64(a + 64 * blk);
            ms = sph_now_ms() - t0;
            if (sum == -1.0f) fputc(' ', stderr); /* keep the loop */
            if (ms > 0) best_read = fmax(best_read, sizeof(float) * (double)n / (ms * 1e6));
        }
        m->triad_gbs[t] = best_triad;
        m->read_gbs[t] = best_read;
    }
out:
    free(a);
    free(b);
    free(c);
}

void bench_machine_measure(bench_machine *m, bool quick)
{
    memset(m, 0, sizeof *m);
#ifdef _OPENMP
    m->cores = omp_get_num_procs();
#else
    m->cores = 1;
#endif
    m->mhz_cpuinfo = cpuinfo_mhz();
    m->clock_ghz = measure_clock_ghz(quick);
    m->lanes = vector_lanes();
    m->fma_gflops[0] = measure_fma(1, quick);
    m->fma_gflops[1] = measure_fma(m->cores, quick);
    bench_machine_peak(m);
    measure_stream(m, quick);
}

void bench_machine_print(FILE *f, const bench_machine *m)
{
    fprintf(f, "cores            %d\n", m->cores);
    fprintf(f, "clock            %.2f GHz measured (dependent integer multiplications), /proc/cpuinfo says %.0f MHz\n",
            m->clock_ghz, m->mhz_cpuinfo);
    fprintf(f, "vector width     %d floats (%s)\n", m->lanes,
            m->lanes == 16 ? "AVX-512" : m->lanes == 8 ? "AVX2" : "scalar build");
    fprintf(f, "FMA throughput   %.1f GFLOP/s on 1 core, %.1f on %d cores (12 independent FMA chains)\n",
            m->fma_gflops[0], m->fma_gflops[1], m->cores);
    if (m->clock_low)
        fprintf(f, "float peak       %.1f GFLOP/s per core: the FMA throughput measured, since %.2f GHz x %d lanes x 2 "
                   "(FMA) x %d FMA pipe%s is less (the clock read low: a busy host)\n",
                m->peak_gflops_core, m->clock_ghz, m->lanes, m->fma_pipes, m->fma_pipes == 1 ? "" : "s");
    else
        fprintf(f, "float peak       %.1f GFLOP/s per core = %.2f GHz x %d lanes x 2 (FMA) x %d FMA pipe%s\n",
                m->peak_gflops_core, m->clock_ghz, m->lanes, m->fma_pipes, m->fma_pipes == 1 ? "" : "s");
    fprintf(f, "memory (triad)   %.1f GB/s on 1 core, %.1f on %d cores (a = b + s c, %.0f MB arrays)\n",
            m->triad_gbs[0], m->triad_gbs[1], m->cores, m->array_mb);
    fprintf(f, "memory (read)    %.1f GB/s on 1 core, %.1f on %d cores (sum of a)\n", m->read_gbs[0], m->read_gbs[1],
            m->cores);
}

cJSON *bench_machine_to_json(const bench_machine *m)
{
    cJSON *o = cJSON_CreateObject();
    /* figures rounded as the table prints them: more digits would be noise */
    bool ok = o && cJSON_AddNumberToObject(o, "cores", m->cores) && sph_json_add_num(o, "clock_ghz", m->clock_ghz, 4) &&
              sph_json_add_num(o, "cpuinfo_mhz", m->mhz_cpuinfo, 6) && cJSON_AddNumberToObject(o, "vector_lanes", m->lanes) &&
              cJSON_AddNumberToObject(o, "fma_pipes", m->fma_pipes) &&
              sph_json_add_num(o, "peak_gflops_per_core", m->peak_gflops_core, 4) &&
              cJSON_AddBoolToObject(o, "peak_is_the_fma_measured", m->clock_low) &&
              sph_json_add_num(o, "fma_gflops_1_core", m->fma_gflops[0], 4) &&
              sph_json_add_num(o, "fma_gflops_all_cores", m->fma_gflops[1], 4) &&
              sph_json_add_num(o, "triad_gbs_1_core", m->triad_gbs[0], 4) &&
              sph_json_add_num(o, "triad_gbs_all_cores", m->triad_gbs[1], 4) &&
              sph_json_add_num(o, "read_gbs_1_core", m->read_gbs[0], 4) &&
              sph_json_add_num(o, "read_gbs_all_cores", m->read_gbs[1], 4) && sph_json_add_num(o, "array_mb", m->array_mb, 4);
    if (ok) return o;
    cJSON_Delete(o);
    return NULL;
}
