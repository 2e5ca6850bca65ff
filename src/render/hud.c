/* The renderer's text and layout (see renderer_impl.h): where the view,
 * legend, index strip and side column go (the arithmetic in layout.c), the HUD with its pass timings, the window's
 * panel, the colour legend and the overlay builder's notes. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "layout.h"
#include "renderer_impl.h"

/* ---- layout, notes --------------------------------------------------------- */

bool hud_layout(sph_renderer *r, const sph_sim *sim, unsigned layers, int side_w, int rc[4], int *legend_w)
{
    const bool strip = (layers & SPH_OV_BIT(INDEX)) && sim->in_pipeline[SPH_PASS_HASH];
    const bool legend = layers & SPH_OV_BIT(LEGEND);
    sph_layout L;
    sph_layout_compute(r->w, r->h, side_w, legend, strip, &L);
    memcpy(rc, L.view, sizeof L.view);
    memcpy(r->legend, L.legend, sizeof r->legend);
    memcpy(r->strip, L.strip, sizeof r->strip);
    memcpy(r->side, L.side, sizeof r->side);
    r->side_used = 0;
    *legend_w = legend ? L.side[0] - L.legend[0] : 0; /* the legend column, right edge at the side column */
    return strip;
}

void hud_notes(sph_renderer *r, const int rc[4])
{
    if (!r->ov.note[0]) return;
    const float fs = r->font.px[SPH_TEXT_SMALL];
    /* the builder joins its notes with "; ": one line each, upwards from the view's bottom */
    char notes[sizeof r->ov.note];
    snprintf(notes, sizeof notes, "%s", r->ov.note);
    float y = (float)(rc[1] + rc[3]) - 0.8f * fs;
    char *parts[8];
    int np = 0;
    for (char *save = NULL, *t = strtok_r(notes, ";", &save); t && np < 8; t = strtok_r(NULL, ";", &save))
        parts[np++] = t + (*t == ' ');
    for (int k = np - 1; k >= 0; k--, y -= 1.3f * fs)
        canvas_text_at(r, SPH_TEXT_SMALL, (float)rc[0] + 4, y, SPH_ALIGN_LEFT, SPH_RGBA(255, 220, 120, 255), parts[k], true);
}

/* ---- HUD, panel, legend ------------------------------------------------------ */

/* Records this draw and returns the draws per second over the last
 * SPH_STEP_WINDOW of them (0 until there are two). */
static double hud_frames_per_s(sph_renderer *r)
{
    double now = sph_now_ms();
    uint64_t k = r->hud_draws < SPH_STEP_WINDOW ? r->hud_draws : SPH_STEP_WINDOW; /* draws before this one */
    double oldest = k ? r->hud_drawn_ms[(r->hud_draws - k) % SPH_STEP_WINDOW] : now;
    r->hud_drawn_ms[r->hud_draws++ % SPH_STEP_WINDOW] = now;
    return now > oldest ? 1e3 * (double)k / (now - oldest) : 0;
}

typedef struct hud_measure {
    const sph_font *font;
    int size; /* SPH_TEXT_SMALL or SPH_TEXT_NORMAL */
} hud_measure;

static float hud_text_width(const void *ctx, const char *s)
{
    const hud_measure *m = ctx;
    return sph_font_width(m->font, m->size, s);
}

void hud_draw(sph_renderer *r, const sph_sim *sim, const sph_view *v)
{
    const float fn = r->font.px[SPH_TEXT_NORMAL], fs = r->font.px[SPH_TEXT_SMALL];
    const bool timings = v->overlays & SPH_OV_BIT(TIMINGS), hud = v->overlays & SPH_OV_BIT(HUD);
    char lines[24][128];
    int nl = 0;
    if (hud) {
        sph_hud_info info = v->hud;
        if (!timings) info.steps_per_s = -1; /* changes from run to run: only with the timings */
        info.frames_per_s = hud_frames_per_s(r);
        nl = sph_hud_lines(sim, &info, lines, 24);
    }
    int bars = 0;
    double mx = 0;
    if (timings)
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (sim->in_pipeline[p]) {
                bars++;
                if (sim->timing[p].last_ms > mx) mx = sim->timing[p].last_ms;
            }
    if (!nl && !bars) return;
    /* in the side column the lines take the small size, so more fit its width */
    const bool side = r->side[2] > 0;
    const int tsz = side ? SPH_TEXT_SMALL : SPH_TEXT_NORMAL;
    /* the text panel below keeps room for its rows at the tightest spacing, up to half the column */
    float room[4];
    sph_layout_hud_room(r->cam.rect, r->side, r->side_used, v->panel ? sph_hud_panel_reserve(v->panel_lines, fs) : 0,
                        (float)v->panel_keep_px, room);
    const float x0 = room[0], y0 = room[1], max_w = room[2], max_h = room[3];
    const float name_w = sph_font_width(&r->font, SPH_TEXT_SMALL, ">18 density_gradient ");
    const float ms_w = sph_font_width(&r->font, SPH_TEXT_SMALL, " 00.000 ms");
    /* the bar takes what the name and the time leave of the box, 6 normal sizes at most */
    const float bar_w = fmaxf(fminf(6.0f * fn, max_w - 12 - name_w - ms_w), fn);
    static sph_hud_fit fit; /* large (its rows); one renderer draws at a time */
    const hud_measure m = {&r->font, tsz};
    sph_hud_fit_compute((const char(*)[128])lines, nl, bars, name_w + bar_w + ms_w, max_w, max_h, r->font.px[tsz], fs,
                        fn, hud_text_width, &m, &fit);
    if (side) r->side_used = y0 + fit.h - (float)r->side[1];
    canvas_rect(r, x0, y0, x0 + fit.w, y0 + fit.h, SPH_RGBA(0, 0, 0, 160));
    float y = y0 + 4;
    for (int i = 0; i < fit.n_rows; i++, y += fit.text_pitch)
        canvas_text(r, tsz, x0 + 6, y, SPH_RGBA(235, 235, 240, 255), fit.row[i]);
    y += fit.gap;
    int number = 0, drawn = 0;
    for (int p = 0; p < SPH_PASS_COUNT && drawn < fit.n_bars; p++) {
        if (!sim->in_pipeline[p]) continue;
        drawn++;
        bool on = sim->enabled[p];
        uint32_t col = on ? SPH_RGBA(220, 220, 225, 255) : SPH_RGBA(120, 120, 125, 255);
        /* numbered as `sphlab check` numbers them; the window's chosen pass marked */
        char name[40];
        snprintf(name, sizeof name, "%s%d %s", v->hud.pass_cursor == p + 1 ? ">" : "", ++number, sph_passes[p]->name);
        if (v->hud.pass_cursor == p + 1) col = SPH_RGBA(255, 220, 90, 255);
        canvas_text(r, SPH_TEXT_SMALL, x0 + 6, y, col, name);
        double ms = sim->timing[p].last_ms;
        float bw = mx > 0 ? (float)(ms / mx) * bar_w : 0;
        float bx = x0 + 6 + name_w;
        canvas_rect(r, bx, y + 0.2f * fs, bx + bar_w, y + 1.0f * fs, SPH_RGBA(60, 60, 70, 255));
        if (on) canvas_rect(r, bx, y + 0.2f * fs, bx + roundf(bw), y + 1.0f * fs, SPH_RGBA(240, 160, 60, 255));
        char ms_s[32];
        snprintf(ms_s, sizeof ms_s, " %.3f ms", ms);
        canvas_text(r, SPH_TEXT_SMALL, bx + bar_w, y, col, on ? ms_s : " off");
        y += fit.bar_pitch;
    }
}

void hud_panel(sph_renderer *r, const char (*lines)[128], int n, int keep_px)
{
    /* in the side column, below the HUD, when there is one (the window); else at the view's top-right corner */
    const bool side = r->side[2] > 0;
    float room[4];
    sph_layout_hud_room(r->cam.rect, r->side, r->side_used, 0, (float)keep_px, room);
    float x0 = room[0], max_w = room[2];
    const float y0 = room[1], max_h = room[3];
    if (!side) max_w *= 0.5f; /* the right half of the view: the HUD has the left */
    static sph_hud_fit fit;
    const hud_measure m = {&r->font, SPH_TEXT_SMALL};
    const float fs = r->font.px[SPH_TEXT_SMALL];
    sph_hud_fit_compute(lines, n, 0, 0, max_w, max_h, fs, fs, r->font.px[SPH_TEXT_NORMAL], hud_text_width, &m, &fit);
    if (!side) x0 = (float)(r->cam.rect[0] + r->cam.rect[2]) - 4 - fit.w;
    canvas_rect(r, x0, y0, x0 + fit.w, y0 + fit.h, SPH_RGBA(0, 0, 0, 185));
    if (side) r->side_used = y0 + fit.h - (float)r->side[1];
    for (int i = 0; i < fit.n_rows; i++)
        canvas_text(r, SPH_TEXT_SMALL, x0 + 6, y0 + 4 + (float)i * fit.text_pitch, SPH_RGBA(235, 235, 240, 255),
                    fit.row[i]);
}

void hud_legend(sph_renderer *r, const sph_sim *sim, sph_color_field f, float lo, float hi)
{
    const float fn = r->font.px[SPH_TEXT_NORMAL], fs = r->font.px[SPH_TEXT_SMALL];
    const float x0 = (float)r->legend[0], y0 = (float)r->legend[1], w = (float)r->legend[2], hgt = (float)r->legend[3];
    const uint32_t white = SPH_RGBA(235, 235, 240, 255), grey = SPH_RGBA(170, 170, 180, 255);
    char unit[48];
    snprintf(unit, sizeof unit, "[%s]", sph_color_field_unit(f, sim->dim));
    /* the field's name centred over the bar; one wider than the column (pcisph-pressure at 800 x 600 ran past the
     * frame's right edge) in the small size, its right end kept inside the column */
    const char *name = sph_color_field_names[f];
    const int size = sph_font_width(&r->font, SPH_TEXT_NORMAL, name) > w - 4 ? SPH_TEXT_SMALL : SPH_TEXT_NORMAL;
    const float tw = sph_font_width(&r->font, size, name);
    const float cx = fminf(x0 + 0.5f * w, x0 + w - 2 - 0.5f * tw);
    canvas_text_at(r, size, cx, y0 + 0.6f * fn, SPH_ALIGN_CENTER, white, name, false);
    canvas_text_at(r, SPH_TEXT_SMALL, x0 + 0.5f * w, y0 + 0.6f * fn + 1.2f * fs, SPH_ALIGN_CENTER, grey, unit, false);
    float top = y0 + 1.4f * fn + 1.6f * fs, bot = y0 + hgt - fs;
    float bx0 = x0 + 4, bx1 = bx0 + fn;
    if (bot - top < 20) return;
    char s[32];
    if (sph_color_field_categorical(f)) {
        float cell = (bot - top) / 10.0f;
        for (int k = 0; k < 10; k++) {
            float ya = top + cell * (float)k;
            canvas_rect(r, bx0, ya + 1, bx1, ya + cell - 1, sph_colormap_category((uint32_t)k));
            snprintf(s, sizeof s, "%d", k);
            canvas_text_at(r, SPH_TEXT_SMALL, bx1 + 4, ya + 0.5f * cell, SPH_ALIGN_LEFT, white, s, false);
        }
        canvas_text_at(r, SPH_TEXT_SMALL, x0 + 0.5f * w, bot + 0.5f * fs, SPH_ALIGN_CENTER, grey, "key mod 10", false);
        return;
    }
    /* the bar, top = max; one band per pixel row */
    for (float y = top; y < bot; y += 1.0f) {
        float t = 1.0f - (y + 0.5f - top) / (bot - top);
        canvas_rect(r, bx0, y, bx1, fminf(y + 1.0f, bot), sph_colormap_viridis(t));
    }
    canvas_outline(r, bx0 - 1, top - 1, bx1 + 1, bot + 1, 1, grey);
    if (!(hi > lo)) { /* one value everywhere (a speed at step 0): said once, not as "0 / 0 / 0" */
        sph_legend_label(s, sizeof s, lo, lo, hi);
        canvas_text_at(r, SPH_TEXT_SMALL, bx1 + 4, 0.5f * (top + bot), SPH_ALIGN_LEFT, white, s, false);
        canvas_text_at(r, SPH_TEXT_SMALL, bx1 + 4, 0.5f * (top + bot) + 1.2f * fs, SPH_ALIGN_LEFT, grey, "everywhere",
                       false);
        return;
    }
    sph_legend_label(s, sizeof s, hi, lo, hi);
    canvas_text_at(r, SPH_TEXT_SMALL, bx1 + 4, top + 0.5f * fs, SPH_ALIGN_LEFT, white, s, false);
    sph_legend_label(s, sizeof s, 0.5f * (lo + hi), lo, hi);
    canvas_text_at(r, SPH_TEXT_SMALL, bx1 + 4, 0.5f * (top + bot), SPH_ALIGN_LEFT, white, s, false);
    sph_legend_label(s, sizeof s, lo, lo, hi);
    canvas_text_at(r, SPH_TEXT_SMALL, bx1 + 4, bot - 0.5f * fs, SPH_ALIGN_LEFT, white, s, false);
}
