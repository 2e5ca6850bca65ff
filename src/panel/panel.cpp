// The window's parameter panel (panel.h): Dear ImGui widgets made from the
// scene key table. Every widget edits a copy of the definition; an edit is
// handed back as the key's text (sph_scene_value_text), so the window applies
// it through the same parser as a --set option.

// the C headers first, with C linkage (panel.h includes sph_scene.h again, guarded)
extern "C" {
#include "sph_scene.h"
}
#include "panel.h"

#include <SDL.h>
#include <imgui.h>
#include <backends/imgui_impl_opengl3.h>
#include <backends/imgui_impl_sdl.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>

struct sph_panel {
    ImGuiContext *ctx;
    bool sdl_ok, gl_ok;
    char save_path[1024];
    const sph_panel_ladder *ladder;
};

extern "C" void sph_panel_set_ladder(sph_panel *p, const sph_panel_ladder *ladder)
{
    p->ladder = ladder;
}

// The ladder and the passes: a level list, N, validate, the passes by number.
static void ladder_widgets(const sph_panel_ladder *l, sph_panel_out *out)
{
    const char *now = l->level >= 0 && l->level < l->n_levels ? l->level_name[l->level] : "none";
    if (ImGui::BeginCombo("level", now)) {
        for (int k = 0; k < l->n_levels; k++) {
            char row[128];
            std::snprintf(row, sizeof row, "%s  %s", l->level_name[k], l->level_about[k]);
            if (ImGui::Selectable(row, k == l->level) && k != l->level) out->level = k;
        }
        ImGui::EndCombo();
    }
    ImGui::Text("%u particles", l->particles);
    ImGui::SameLine();
    if (ImGui::Button("x2")) out->particles = 1;
    ImGui::SameLine();
    if (ImGui::Button("/2")) out->particles = -1;
    if (ImGui::Button("validate vs L0")) out->validate = 1;
    ImGui::SameLine();
    if (ImGui::Button("vs L2")) out->validate = 2;
    ImGui::TextUnformatted("passes (numbers as sphlab check's)");
    for (int k = 0; k < l->n_passes; k++) {
        char row[64];
        std::snprintf(row, sizeof row, "%2d %s", k + 1, l->pass_name[k]);
        bool on = l->pass_on[k];
        if (k % 2) ImGui::SameLine(ImGui::GetFontSize() * 11.0f);
        if (ImGui::Checkbox(row, &on)) out->pass = k;
    }
}

extern "C" sph_panel *sph_panel_create(SDL_Window *win, void *gl_context, const char *save_path,
                                      const char *font_path, char *err, size_t n)
{
    sph_panel *p = static_cast<sph_panel *>(std::calloc(1, sizeof(sph_panel)));
    if (!p) {
        std::snprintf(err, n, "out of memory for the panel");
        return NULL;
    }
    std::snprintf(p->save_path, sizeof p->save_path, "%s", save_path ? save_path : "scene.ini");
    p->ctx = ImGui::CreateContext();
    ImGuiIO &io = ImGui::GetIO();
    io.IniFilename = NULL; // no imgui.ini in the user's folder
    io.LogFilename = NULL;
    ImGui::StyleColorsDark();
    // the renderer's face at its normal size for a 720-pixel window; ImGui's own font without it
    FILE *f = font_path ? std::fopen(font_path, "rb") : NULL;
    if (f) {
        std::fclose(f);
        io.Fonts->AddFontFromFileTTF(font_path, SPH_PANEL_FONT_PX);
    }
    p->sdl_ok = ImGui_ImplSDL2_InitForOpenGL(win, gl_context);
    p->gl_ok = p->sdl_ok && ImGui_ImplOpenGL3_Init("#version 330 core");
    if (!p->gl_ok) {
        std::snprintf(err, n, "Dear ImGui cannot start on this window's OpenGL (%s)", p->sdl_ok ? "OpenGL 3 backend" : "SDL2 backend");
        sph_panel_destroy(p);
        return NULL;
    }
    return p;
}

extern "C" void sph_panel_destroy(sph_panel *p)
{
    if (!p) return;
    ImGui::SetCurrentContext(p->ctx);
    if (p->gl_ok) ImGui_ImplOpenGL3_Shutdown();
    if (p->sdl_ok) ImGui_ImplSDL2_Shutdown();
    ImGui::DestroyContext(p->ctx);
    std::free(p);
}

extern "C" bool sph_panel_event(sph_panel *p, const SDL_Event *e)
{
    ImGui::SetCurrentContext(p->ctx);
    ImGui_ImplSDL2_ProcessEvent(e);
    const ImGuiIO &io = ImGui::GetIO();
    switch (e->type) {
    case SDL_MOUSEMOTION:
    case SDL_MOUSEBUTTONDOWN:
    case SDL_MOUSEBUTTONUP:
    case SDL_MOUSEWHEEL: return io.WantCaptureMouse;
    case SDL_KEYDOWN:
    case SDL_KEYUP:
    case SDL_TEXTINPUT: return io.WantCaptureKeyboard || io.WantTextInput;
    default: return false;
    }
}

// ---- one widget per key --------------------------------------------------

// The slider's span for a number key: its accepted range where that is
// narrow; else two decades each side of the value (or default), as a
// logarithmic slider when it spans decades. Ctrl+click types any value; the
// parser checks it against the real range.
static void slider_span(const sph_key *k, double v, float *lo, float *hi, bool *log_scale)
{
    double a = k->min, b = k->max;
    double ref = v != 0 ? std::fabs(v) : std::fabs(std::atof(k->def));
    if (a < 0) { // a signed value: linear, symmetric about 0
        double m = ref > 0 ? 10 * ref : 1;
        a = std::fmax(a, -m);
        b = std::fmin(b, m);
        *log_scale = false;
    } else {
        if (b - a > 1000 * (ref > 0 ? ref : 1)) { // a wide range: around the value
            b = std::fmin(b, ref > 0 ? 100 * ref : 10);
            a = std::fmax(a, ref > 0 ? ref / 100 : a);
        }
        *log_scale = b / std::fmax(a, 1e-12) >= 100 || (a == 0 && b >= 100 * (ref > 0 ? ref : 1));
    }
    if (v < a) a = v;
    if (v > b) b = v;
    if (k->min_open && a <= k->min) a = (float)(k->min + (b - k->min) * 1e-6);
    *lo = (float)a;
    *hi = (float)b;
}

static void tooltip(const sph_key *k)
{
    if (!ImGui::IsItemHovered()) return;
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 28.0f);
    ImGui::TextUnformatted(k->help);
    ImGui::TextDisabled("[%s] %s%s%sdefault %s", k->section, k->name, *k->unit ? ", unit " : "", k->unit, k->def);
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
}

// One key's widget over the value at base (a copy); true once an edit is finished.
static bool key_widget(const sph_key *k, void *base, int dim)
{
    char *field = static_cast<char *>(base) + k->offset;
    const char *label = k->name;
    char fmt[48];
    std::snprintf(fmt, sizeof fmt, "%%.4g%s%s", *k->unit ? " " : "", k->unit);
    bool done = false;
    switch (k->type) {
    case SPH_KEY_FLOAT: {
        float v;
        std::memcpy(&v, field, sizeof v);
        float lo, hi;
        bool log_scale;
        slider_span(k, v, &lo, &hi, &log_scale);
        ImGuiSliderFlags flags = log_scale ? ImGuiSliderFlags_Logarithmic | ImGuiSliderFlags_NoRoundToFormat : 0;
        ImGui::SliderFloat(label, &v, lo, hi, fmt, flags);
        done = ImGui::IsItemDeactivatedAfterEdit();
        std::memcpy(field, &v, sizeof v);
        break;
    }
    case SPH_KEY_INT:
    case SPH_KEY_UINT: {
        const bool u = k->type == SPH_KEY_UINT;
        if (k->max - k->min <= 16) {
            int v;
            std::memcpy(&v, field, sizeof v);
            ImGui::SliderInt(label, &v, (int)k->min, (int)k->max);
            std::memcpy(field, &v, sizeof v);
        } else {
            ImGui::InputScalar(label, u ? ImGuiDataType_U32 : ImGuiDataType_S32, field);
        }
        done = ImGui::IsItemDeactivatedAfterEdit();
        break;
    }
    case SPH_KEY_VEC: {
        float v[3];
        std::memcpy(v, field, sizeof v);
        if (dim == 2)
            ImGui::DragFloat2(label, v, 0.01f, 0, 0, fmt);
        else
            ImGui::DragFloat3(label, v, 0.01f, 0, 0, fmt);
        done = ImGui::IsItemDeactivatedAfterEdit();
        std::memcpy(field, v, sizeof v);
        break;
    }
    case SPH_KEY_POINT: { // a position kept in double (exact far from 0)
        double v[3];
        std::memcpy(v, field, sizeof v);
        ImGui::InputScalarN(label, ImGuiDataType_Double, v, dim, nullptr, nullptr, "%.6g");
        done = ImGui::IsItemDeactivatedAfterEdit();
        std::memcpy(field, v, sizeof v);
        break;
    }
    case SPH_KEY_CHOICE:
    case SPH_KEY_KERNEL: {
        int v;
        std::memcpy(&v, field, sizeof v);
        if (ImGui::BeginCombo(label, v >= 0 && v < k->n_choices ? k->choices[v] : "?")) {
            for (int c = 0; c < k->n_choices; c++)
                if (ImGui::Selectable(k->choices[c], c == v) && c != v) {
                    v = c;
                    done = true;
                }
            ImGui::EndCombo();
        }
        std::memcpy(field, &v, sizeof v);
        break;
    }
    case SPH_KEY_FLAGS: {
        unsigned v;
        std::memcpy(&v, field, sizeof v);
        ImGui::TextUnformatted(label);
        for (int c = 0; c < k->n_choices; c++) {
            bool on = (v >> c) & 1u;
            if (c % 3) ImGui::SameLine(ImGui::GetFontSize() * 8.0f * (float)(c % 3));
            if (ImGui::Checkbox(k->choices[c], &on)) {
                v ^= 1u << c;
                done = true;
            }
        }
        std::memcpy(field, &v, sizeof v);
        break;
    }
    case SPH_KEY_STRING:
        ImGui::InputText(label, field, 64);
        done = ImGui::IsItemDeactivatedAfterEdit();
        break;
    }
    tooltip(k);
    return done;
}

// The keys of one section (or of the fluid block b), over the copy edit; the
// first finished edit becomes out->set.
static void section_widgets(const char *section, int b, sph_scene_def *edit, sph_panel_out *out)
{
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (std::strcmp(k->section, section) != 0) continue;
        void *base = b >= 0 ? static_cast<void *>(&edit->blocks[b]) : static_cast<void *>(edit);
        ImGui::PushID(i);
        bool done = key_widget(k, base, edit->dim);
        ImGui::PopID();
        if (!done || out->set[0]) continue;
        char value[256];
        sph_scene_value_text(k, base, value, sizeof value);
        if (b >= 0)
            std::snprintf(out->set, sizeof out->set, "fluid %s.%s=%s", edit->blocks[b].name, k->name, value);
        else
            std::snprintf(out->set, sizeof out->set, "%s.%s=%s", section, k->name, value);
    }
}

static bool first_of_section(int i)
{
    for (int j = 0; j < i; j++)
        if (std::strcmp(sph_scene_keys[j].section, sph_scene_keys[i].section) == 0) return false;
    return true;
}

extern "C" void sph_panel_frame(sph_panel *p, const sph_scene_def *def, const int rect[4], const char *message,
                                sph_panel_out *out)
{
    out->set[0] = out->save[0] = '\0';
    out->level = out->pass = -1;
    out->particles = out->validate = 0;
    ImGui::SetCurrentContext(p->ctx);
    ImGui_ImplOpenGL3_NewFrame();
    ImGui_ImplSDL2_NewFrame();
    ImGui::NewFrame();
    ImGui::SetNextWindowPos(ImVec2((float)rect[0], (float)rect[1]));
    ImGui::SetNextWindowSize(ImVec2((float)rect[2], (float)rect[3]));
    const ImGuiWindowFlags wf = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                ImGuiWindowFlags_NoSavedSettings;
    if (ImGui::Begin("parameters (tab hides)", NULL, wf)) {
        ImGui::PushItemWidth(-ImGui::GetFontSize() * 8.0f);
        ImGui::InputText("##save", p->save_path, sizeof p->save_path);
        ImGui::SameLine();
        if (ImGui::Button("Save scene as") && p->save_path[0])
            std::snprintf(out->save, sizeof out->save, "%s", p->save_path);
        if (message && *message) ImGui::TextWrapped("%s", message);
        ImGui::Separator();
        if (p->ladder && ImGui::CollapsingHeader("ladder and passes", ImGuiTreeNodeFlags_DefaultOpen)) {
            ImGui::PushID("ladder");
            ladder_widgets(p->ladder, out);
            ImGui::PopID();
        }
        sph_scene_def edit = *def; // the widgets edit a copy: the window applies a finished edit
        for (int i = 0; i < sph_scene_key_count; i++) {
            if (!first_of_section(i)) continue;
            const char *section = sph_scene_keys[i].section;
            if (std::strcmp(section, "fluid") == 0) {
                for (int b = 0; b < edit.n_blocks; b++) {
                    char head[80];
                    std::snprintf(head, sizeof head, "fluid %s", edit.blocks[b].name);
                    ImGui::PushID(1000 + b);
                    if (ImGui::CollapsingHeader(head)) section_widgets(section, b, &edit, out);
                    ImGui::PopID();
                }
                continue;
            }
            const bool open = std::strcmp(section, "physics") == 0 || std::strcmp(section, "kernels") == 0 ||
                              std::strcmp(section, "time") == 0;
            if (ImGui::CollapsingHeader(section, open ? ImGuiTreeNodeFlags_DefaultOpen : 0))
                section_widgets(section, -1, &edit, out);
        }
        ImGui::PopItemWidth();
    }
    ImGui::End();
    ImGui::Render();
}

extern "C" void sph_panel_draw(sph_panel *p)
{
    ImGui::SetCurrentContext(p->ctx);
    ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}
