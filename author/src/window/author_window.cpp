// The authoring window; see author_window.hpp.
#include "tactile/author/author_window.hpp"

#include <GLFW/glfw3.h>
#include <fcntl.h>
#include <fmt/format.h>
#include <imgui.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <future>
#include <stdexcept>
#include <thread>

#include "tactile/author/remapper.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/viewer_gl.hpp"
#include "tactile/mapping/strain_panel.hpp"
#include "tactile/movie/frame_geometry.hpp"

namespace tactile::author {

namespace {

using Clock = std::chrono::steady_clock;

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// One of the two mappings the window compares: what was asked and the newest outcome of it.
struct Slot {
  mapping::MapRequest request;
  std::shared_ptr<const MappingOutcome> outcome;
};

// An audition on its own thread; a pipe is its stop signal (play ramps to rest when it reads).
class Audition {
 public:
  Audition() {
    if (::pipe2(stop_pipe_, O_CLOEXEC | O_NONBLOCK) != 0) {
      throw std::runtime_error("audition: cannot make its stop pipe");
    }
  }
  ~Audition() {
    stop();
    ::close(stop_pipe_[0]);
    ::close(stop_pipe_[1]);
  }
  Audition(const Audition&) = delete;
  Audition& operator=(const Audition&) = delete;

  bool running() const {
    return result_.valid() &&
           result_.wait_for(std::chrono::seconds(0)) != std::future_status::ready;
  }
  void start(movie::TactileMovie movie, int loops, const display::PlayBackends& backends,
             const std::optional<display::LateroPlayTarget>& latero,
             std::function<void(const std::string&)> say) {
    stop();
    drain();
    error_.clear();
    say_ = say;
    display::ResolvedPlay request;
    request.loops = loops;
    request.latero = latero;
    request.stop_fd = stop_pipe_[0];
    result_ = std::async(std::launch::async, [movie = std::move(movie), request, backends, say] {
      return display::play_anywhere(
          movie, request,
          [&](const std::string& text) {
            // play says whole lines, each ending in a newline: one event a line.
            std::size_t start = 0;
            while (start < text.size()) {
              const std::size_t end = std::min(text.find('\n', start), text.size());
              if (end > start) say("audition: " + text.substr(start, end - start));
              start = end + 1;
            }
          },
          backends);
    });
  }
  // Stops an audition under way (the device ramps to rest) and returns its result.
  std::optional<display::PlayResult> stop() {
    if (!result_.valid()) return std::nullopt;
    if (running()) {
      const char byte = 1;
      [[maybe_unused]] const auto n = ::write(stop_pipe_[1], &byte, 1);
    }
    return collect();
  }
  // Why the last audition failed (empty: it did not).
  const std::string& error() const { return error_; }
  // The finished audition's result, once.
  std::optional<display::PlayResult> finished() {
    if (!result_.valid() || running()) return std::nullopt;
    return collect();
  }

 private:
  std::optional<display::PlayResult> collect() {
    try {
      display::PlayResult r = result_.get();
      drain();
      return r;
    } catch (const std::exception& e) {
      drain();
      error_ = e.what();
      if (say_) say_("author: audition failed: " + error_);
      return std::nullopt;
    }
  }
  void drain() {
    char buf[16];
    while (::read(stop_pipe_[0], buf, sizeof buf) > 0) {
    }
  }
  int stop_pipe_[2] = {-1, -1};
  std::future<display::PlayResult> result_;
  std::function<void(const std::string&)> say_;
  std::string error_;
};

template <typename E, std::size_t N>
E cycle(const std::array<Named<E>, N>& table, E value, int step) {
  std::size_t i = 0;
  while (i < N && table[i].value != value) ++i;
  return table[(i + N + static_cast<std::size_t>(step + static_cast<int>(N))) % N].value;
}

std::string next_layout(const std::string& layout, int step) {
  const auto& names = movie::kBuiltinLayoutNames;
  const auto n = static_cast<int>(names.size());
  int i = 0;
  while (i < n && names[static_cast<std::size_t>(i)] != layout) ++i;
  if (i == n) i = step > 0 ? -1 : 0;  // a file layout: on to the built-in ones
  return std::string(names[static_cast<std::size_t>((i + step + n) % n)]);
}

// The next display rate the R key gives: the layout's own (unset), then a half and a quarter of
// it in whole hertz, then the layout's own again.
std::optional<double> next_rate(const mapping::MapRequest& request, const MappingOutcome* shown) {
  if (shown == nullptr || !shown->error.empty()) return std::nullopt;
  const double own = shown->layout.max_rate_hz;
  if (!request.params.rate_hz) return std::floor(own / 2);
  if (*request.params.rate_hz > own / 3) return std::floor(own / 4);
  return std::nullopt;
}

// The panel's control for one row of the mapping's option table; true when the request
// changed (and passed the row's checks).
// `typed` holds what is typed into a path's text field between frames.
bool option_control(const OptionRow<mapping::MapRequest>& row, mapping::MapRequest& request,
                    std::string& problem, std::array<char, 512>& typed) {
  const std::string label = option_label(row.name, OptionSpelling::cli);
  const std::string id = "##" + std::string(row.name);
  const OptionValue value = row.get(request);
  auto apply = [&](const OptionValue& v) {
    if (std::string p = option_problem(row, v); !p.empty()) {
      problem = label + ": " + p;
      return false;
    }
    problem.clear();
    row.set(request, v);
    return true;
  };
  ImGui::TextUnformatted(fmt::format("{}{}{}", label, row.unit.empty() ? "" : " (",
                                     row.unit.empty() ? "" : std::string(row.unit) + ")")
                             .c_str());
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", row.help.c_str());
  switch (row.kind) {
    case OptionKind::choice: {
      const auto& current = std::get<std::string>(value);
      bool changed = false;
      if (ImGui::BeginCombo(id.c_str(), current.c_str())) {
        for (const auto& c : row.choices) {
          if (ImGui::Selectable(c.c_str(), c == current) && c != current) changed = apply(c);
        }
        ImGui::EndCombo();
      }
      return changed;
    }
    case OptionKind::path: {
      // The layout: built-in names in a list, or a layout file typed in (applied on Enter).
      const auto& current = std::get<std::string>(value);
      bool changed = false;
      if (ImGui::BeginCombo(id.c_str(), current.c_str())) {
        for (const auto name : movie::kBuiltinLayoutNames) {
          const std::string n(name);
          if (ImGui::Selectable(n.c_str(), n == current) && n != current) changed = apply(n);
        }
        ImGui::EndCombo();
      }
      if (ImGui::InputTextWithHint((id + "file").c_str(), "or a layout FILE.json, Enter",
                                   typed.data(), typed.size(),
                                   ImGuiInputTextFlags_EnterReturnsTrue)) {
        changed = apply(std::string(typed.data()));
      }
      return changed;
    }
    case OptionKind::integer:
    case OptionKind::number: {
      const bool unset = std::holds_alternative<std::monostate>(value);
      if (row.optional) {
        bool use_default = unset;
        if (ImGui::Checkbox(("default" + id).c_str(), &use_default)) {
          return apply(use_default ? OptionValue{}
                                   : OptionValue{row.min < 1 && row.max > 1000 ? 1000.0 : row.min});
        }
        if (unset) return false;
        ImGui::SameLine();
      }
      double v = 0;
      if (const auto* i = std::get_if<std::int64_t>(&value)) v = static_cast<double>(*i);
      if (const auto* d = std::get_if<double>(&value)) v = *d;
      double edited = v;
      const double step = row.kind == OptionKind::integer ? 1 : std::max(std::abs(v) * 0.1, 0.001);
      if (ImGui::InputDouble(id.c_str(), &edited, step, step * 10, "%g",
                             ImGuiInputTextFlags_EnterReturnsTrue) ||
          (edited != v && ImGui::IsItemDeactivatedAfterEdit())) {
        if (edited == v) return false;
        if (row.kind == OptionKind::integer) {
          if (edited != std::round(edited)) {
            problem = fmt::format("{}: {} is not a whole number", label, edited);
            return false;
          }
          return apply(static_cast<std::int64_t>(edited));
        }
        return apply(edited);
      }
      return false;
    }
    case OptionKind::flag:
    case OptionKind::text:
    case OptionKind::seed:
    case OptionKind::choice_list:
      return false;  // the mapping's table has none
  }
  return false;
}

// A looped audition plays the movie this many times unless stopped first (on a device, as many
// seconds as the movie lasts, times this: about a minute and a half of the demo's).
constexpr int kLoopedAuditionLoops = 100;

constexpr std::array<std::uint8_t, 3> kSaturatedRgb{230, 40, 40};
constexpr std::array<std::uint8_t, 3> kSlewRgb{240, 210, 40};

// Outlines the contactors at a limit at display frame `f`: red at the deflection range's end,
// yellow where the step from the frame before is slew-limited.
int outline_limits(const MappingOutcome& o, std::int32_t f, double magnification,
                   const display::PixelRect& pane) {
  const movie::ViewTransform t = display::pane_view(o.layout, magnification, pane);
  const auto shapes = movie::frame_shapes(o.layout, o.movie.frame(f), magnification);
  const auto n = static_cast<std::size_t>(o.layout.contactor_count());
  int marked = 0;
  glLineWidth(3);
  for (std::size_t j = 0; j < shapes.size() && j < n; ++j) {
    const double d = o.movie.deflection_um[static_cast<std::size_t>(f) * n + j];
    const bool saturated = mapping::at_deflection_limit(o.layout, d);
    const bool slewed =
        f > 0 &&
        mapping::at_slew_limit(d - o.movie.deflection_um[static_cast<std::size_t>(f - 1) * n + j],
                               o.params.slew_limit_um_per_s, o.movie.rate_hz);
    if (!saturated && !slewed) continue;
    ++marked;
    const auto rgb = saturated ? kSaturatedRgb : kSlewRgb;
    const auto& c = shapes[j];
    const double x0 = t.origin_x_px + (c.x_mm - c.width_mm / 2) * t.px_per_mm - 2;
    const double x1 = t.origin_x_px + (c.x_mm + c.width_mm / 2) * t.px_per_mm + 2;
    const double y0 = t.origin_y_px + (c.y_mm - c.height_mm / 2) * t.px_per_mm - 2;
    const double y1 = t.origin_y_px + (c.y_mm + c.height_mm / 2) * t.px_per_mm + 2;
    display::gl::outline_rect(x0, y0, x1, y1, rgb);
  }
  glLineWidth(1);
  return marked;
}

std::string describe_request(const mapping::MapRequest& r) {
  return fmt::format("{} {} gain {:g} normalise {} strain {}", r.layout, to_string(r.params.method),
                     r.params.gain_um_per_strain, to_string(r.params.normalisation),
                     to_string(r.params.strain));
}

struct KeyPress {
  int key = 0;
  int mods = 0;
};
struct KeyQueue {
  std::vector<KeyPress> pressed;
};

void on_key(GLFWwindow* window, int key, int /*scancode*/, int action, int mods) {
  const bool repeatable = key == GLFW_KEY_LEFT || key == GLFW_KEY_RIGHT;
  if (action == GLFW_PRESS || (action == GLFW_REPEAT && repeatable)) {
    static_cast<KeyQueue*>(glfwGetWindowUserPointer(window))->pressed.push_back({key, mods});
  }
}

const char* const kHelp =
    "Keys (mouse: the panel's controls, drag the bar to seek)\n"
    "  space       play / pause         left/right  step a frame\n"
    "  Home        back to the start\n"
    "  M, shift+M  next / previous method\n"
    "  N           next normalisation   T  next strain mode\n"
    "  Y           next built-in layout\n"
    "  G, shift+G  gain x2 / divided by 2\n"
    "  F, shift+F  peak fraction +/- 0.1\n"
    "  E, shift+E  reference frame +/- 10\n"
    "  R           rate: the layout's own, a half, a quarter\n"
    "  P           pin the current mapping as A\n"
    "  Tab         show A / the current mapping (B)\n"
    "  Enter       audition from here (again: stop, ramping to rest)\n"
    "  O           audition looped / once\n"
    "  S           save: the experiment of A and B, their movies, HJIF and WAV\n"
    "  H, F1       this help            Esc, Q  close";

}  // namespace

AuthorWindowResult run_author_window(std::shared_ptr<const capture::StrainMovie> strain,
                                     const mapping::MapRequest& current,
                                     const std::optional<mapping::MapRequest>& a,
                                     const AuthorWindowOptions& options) {
  const auto say = [&](const std::string& line) {
    if (options.say) options.say(line);
  };
  const movie::SideField field = mapping::strain_side_field(*strain, "measured strain");
  Remapper remapper(strain);
  // A is mapped once, in a remapper of its own, so that the current mapping's stays free.
  std::optional<Remapper> a_mapper;
  std::optional<Slot> slot_a;
  if (a) {
    a_mapper.emplace(strain);
    a_mapper->submit(*a);
    slot_a = Slot{*a, nullptr};
  }
  Slot slot_b{current, nullptr};
  std::uint64_t asked = remapper.submit(current);
  Clock::time_point asked_at = Clock::now();
  bool waiting_view = false;   // a change not drawn yet (the first mapping is not a change)
  std::uint64_t b_number = 0;  // the request slot_b.outcome answers

  AuthorWindowResult result;
  KeyQueue keys;
  display::gl::Window window(options.width_px, options.height_px, options.visible, true,
                             "tactile author", on_key, &keys);
  ImGui::GetIO().FontGlobalScale = window.content_scale();
  ImGui::GetStyle().ScaleAllSizes(window.content_scale());

  bool playing = false, loop_audition = false, show_a = false, help = false;
  double position = 0;  // fractional display frame of the shown mapping
  std::string problem, status;
  std::array<char, 512> typed_layout{};
  Audition audition;
  double last_t = glfwGetTime();
  Clock::time_point first_frame{};
  bool screenshot_ready = false;

  const auto change = [&](const mapping::MapRequest& r) {
    slot_b.request = r;
    asked = remapper.submit(r);
    asked_at = Clock::now();
    waiting_view = true;
    show_a = false;
  };

  while (!window.should_close() && !stop_requested(options.stop_fd)) {
    // Newest outcomes.
    if (const auto done = remapper.latest(); done.outcome && done.outcome != slot_b.outcome) {
      slot_b.outcome = done.outcome;
      b_number = done.number;
      const auto& o = *done.outcome;
      if (o.error.empty()) {
        say(
            fmt::format("author: mapped #{} ({}) in {:.1f} ms (+{:.1f} ms of figures): "
                        "correlation {:.3f}, RMS error {:.3g}, saturated {:.1f} %, slew-limited "
                        "{:.1f} %",
                        done.number, describe_request(o.request), o.map_ms, o.figures_ms,
                        o.metrics.strain_correlation, o.metrics.strain_rms_error,
                        100 * o.metrics.saturated_fraction, 100 * o.metrics.slew_limited_fraction));
      } else {
        say(fmt::format("author: mapping #{} refused: {}", done.number, o.error));
      }
    }
    if (a_mapper && slot_a && !slot_a->outcome) {
      if (auto done = a_mapper->latest(); done.outcome) {
        slot_a->outcome = done.outcome;
        say(fmt::format("author: A mapped ({}){}", describe_request(done.outcome->request),
                        done.outcome->error.empty() ? "" : ": " + done.outcome->error));
      }
    }
    // The shown slot is asked again after the keys: a switch and an audition can come in the
    // same frame, and the audition must play what the switch chose.
    const auto shown_outcome = [&] {
      return show_a && slot_a && slot_a->outcome ? slot_a->outcome : slot_b.outcome;
    };
    const std::shared_ptr<const MappingOutcome> shown = shown_outcome();
    const bool view_current = shown && remapper.latest().number >= asked;

    const auto [fb_w, fb_h] = window.framebuffer_px();
    const float scale = window.content_scale();
    const int panel_w = static_cast<int>(340 * scale);
    const int top_h = static_cast<int>(28 * scale);
    const int chart_h = static_cast<int>(150 * scale);
    const int scrub_h = static_cast<int>(24 * scale);
    const int view_w = std::max(fb_w - panel_w, 10);
    const int view_h = std::max(fb_h - top_h - chart_h - scrub_h, 10);
    const display::PixelRect field_pane{panel_w, top_h, view_w / 2, view_h};
    const display::PixelRect array_pane{panel_w + view_w / 2, top_h, view_w - view_w / 2, view_h};
    const display::PixelRect chart_pane{panel_w, top_h + view_h, view_w, chart_h};
    const display::PixelRect scrub_pane{panel_w + 10, fb_h - scrub_h + 4, view_w - 20, scrub_h - 8};

    display::gl::begin_pixels(fb_w, fb_h);
    std::int32_t frame = 0;
    int marked = 0;
    if (shown && shown->error.empty() && shown->movie.frame_count > 0) {
      const auto& m = shown->movie;
      position = std::clamp(position, 0.0, static_cast<double>(m.frame_count - 1));
      frame = static_cast<std::int32_t>(std::floor(position));
      const double t_s = frame / m.rate_hz;
      const std::size_t field_frame = movie::field_frame_at(field, t_s);
      display::gl::draw_field(field, field.frames[field_frame], field_pane);
      const double magnification = movie::auto_magnification(shown->layout);
      const double strain_scale = std::max(movie::movie_strain_full_scale(m), 1e-6);
      display::gl::draw_contactors(shown->layout, m.frame(frame), magnification, strain_scale,
                                   array_pane);
      marked = outline_limits(*shown, frame, magnification, array_pane);
      display::gl::draw_scrub(scrub_pane, frame, m.frame_count);
    }

    display::gl::begin_imgui_frame();
    const ImGuiWindowFlags fixed = ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize |
                                   ImGuiWindowFlags_NoCollapse | ImGuiWindowFlags_NoSavedSettings;
    // The panel: the mapping's choices from its option table, then A/B, audition, save.
    ImGui::SetNextWindowPos(ImVec2(0, 0));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(panel_w), static_cast<float>(fb_h)));
    ImGui::Begin("Mapping", nullptr, fixed);
    ImGui::PushItemWidth(-1);
    // Tab is the A/B key: no control takes the keyboard's focus by it.
    ImGui::PushAllowKeyboardFocus(false);
    mapping::MapRequest edited = slot_b.request;
    bool changed = false;
    for (const auto& row : mapping::map_options()) {
      if (row.positional) continue;
      changed = option_control(row, edited, problem, typed_layout) || changed;
    }
    ImGui::PopAllowKeyboardFocus();
    ImGui::PopItemWidth();
    if (!problem.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", problem.c_str());
    ImGui::Separator();
    bool pin = ImGui::Button("Pin as A (P)");
    ImGui::SameLine();
    bool toggle_ab = ImGui::Button(show_a ? "Show B (Tab)" : "Show A (Tab)");
    bool audition_key = ImGui::Button(audition.running() ? "Stop (Enter)" : "Audition (Enter)");
    ImGui::SameLine();
    ImGui::Checkbox("looped (O)", &loop_audition);
    bool save = ImGui::Button("Save (S)");
    ImGui::SameLine();
    bool help_key = ImGui::Button("Help (H)");
    ImGui::Separator();
    if (slot_b.outcome && !slot_b.outcome->error.empty())
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", slot_b.outcome->error.c_str());
    // A/B table.
    if (slot_b.outcome && slot_b.outcome->error.empty()) {
      const MappingOutcome& b = *slot_b.outcome;
      const MappingOutcome* ao = slot_a && slot_a->outcome && slot_a->outcome->error.empty()
                                     ? slot_a->outcome.get()
                                     : nullptr;
      if (ImGui::BeginTable("ab", ao ? 3 : 2, ImGuiTableFlags_Borders)) {
        ImGui::TableSetupColumn("figure");
        if (ao) ImGui::TableSetupColumn("A");
        ImGui::TableSetupColumn(ao ? "B (current)" : "current");
        ImGui::TableHeadersRow();
        for (const FigureRow& r : compare_figures(ao ? *ao : b, b)) {
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::TextUnformatted(r.name.c_str());
          if (ao) {
            ImGui::TableNextColumn();
            ImGui::Text("%.4g", r.a);
          }
          ImGui::TableNextColumn();
          ImGui::Text("%.4g", r.b);
        }
        ImGui::EndTable();
      }
      if (ao) ImGui::TextWrapped("A -> B: %s", describe_change(ao->request, b.request).c_str());
    }
    if (!status.empty()) ImGui::TextWrapped("%s", status.c_str());
    if (!audition.error().empty())
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "audition: %s", audition.error().c_str());
    ImGui::End();

    // The strip along the top, the chart along the bottom.
    ImGui::SetNextWindowPos(ImVec2(static_cast<float>(panel_w), 0));
    ImGui::SetNextWindowSize(ImVec2(static_cast<float>(view_w), static_cast<float>(top_h)));
    ImGui::Begin("strip", nullptr,
                 fixed | ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoInputs);
    if (shown && shown->error.empty()) {
      ImGui::Text("%s%s   t = %.3f s   frame %d/%d   %s   %d at a limit (red: range, yellow: slew)",
                  show_a ? "A: " : (slot_a ? "B: " : ""), describe_request(shown->request).c_str(),
                  frame / shown->movie.rate_hz, frame + 1, shown->movie.frame_count,
                  view_current || show_a ? "" : "(re-mapping...)", marked);
    } else {
      ImGui::TextUnformatted("mapping...");
    }
    ImGui::End();
    ImGui::SetNextWindowPos(
        ImVec2(static_cast<float>(chart_pane.x), static_cast<float>(chart_pane.y)));
    ImGui::SetNextWindowSize(
        ImVec2(static_cast<float>(chart_pane.width), static_cast<float>(chart_pane.height)));
    ImGui::Begin("Fidelity over time", nullptr, fixed);
    if (shown && shown->error.empty() && !shown->over_time.empty()) {
      std::vector<float> corr, sat, slew;
      for (const auto& p : shown->over_time) {
        corr.push_back(static_cast<float>(p.strain_correlation));
        sat.push_back(static_cast<float>(100 * p.saturated_fraction));
        slew.push_back(static_cast<float>(100 * p.slew_limited_fraction));
      }
      const float w = (static_cast<float>(chart_pane.width) - 40 * scale) / 3;
      const float h = static_cast<float>(chart_pane.height) - 60 * scale;
      ImGui::PlotLines("##corr", corr.data(), static_cast<int>(corr.size()), 0,
                       fmt::format("correlation {:.3f}", shown->metrics.strain_correlation).c_str(),
                       -1, 1, ImVec2(w, h));
      ImGui::SameLine();
      ImGui::PlotLines(
          "##sat", sat.data(), static_cast<int>(sat.size()), 0,
          fmt::format("saturated {:.1f} %", 100 * shown->metrics.saturated_fraction).c_str(), 0,
          100, ImVec2(w, h));
      ImGui::SameLine();
      ImGui::PlotLines(
          "##slew", slew.data(), static_cast<int>(slew.size()), 0,
          fmt::format("slew-limited {:.1f} %", 100 * shown->metrics.slew_limited_fraction).c_str(),
          0, 100, ImVec2(w, h));
    }
    ImGui::End();
    if (help) {
      ImGui::SetNextWindowPos(
          ImVec2(static_cast<float>(panel_w + 40), static_cast<float>(top_h + 40)));
      ImGui::Begin("Help", &help,
                   ImGuiWindowFlags_AlwaysAutoResize | ImGuiWindowFlags_NoSavedSettings);
      ImGui::TextUnformatted(kHelp);
      ImGui::End();
    }

    // Keys, unless a text field has them (queued by the callback: a press and its release can
    // both come between two frames).
    const ImGuiIO& io = ImGui::GetIO();
    std::vector<KeyPress> presses;
    presses.swap(keys.pressed);
    if (!io.WantTextInput) {
      for (const KeyPress& k : presses) {
        const bool shift = (k.mods & GLFW_MOD_SHIFT) != 0;
        switch (k.key) {
          case GLFW_KEY_SPACE:
            playing = !playing;
            break;
          case GLFW_KEY_RIGHT:
            playing = false;
            position = std::floor(position) + 1;
            break;
          case GLFW_KEY_LEFT:
            playing = false;
            position = std::max(std::floor(position) - 1, 0.0);
            break;
          case GLFW_KEY_HOME:
            position = 0;
            break;
          case GLFW_KEY_M:
            edited.params.method =
                cycle(mapping::kMappingMethodNames, edited.params.method, shift ? -1 : 1);
            if (edited.params.method == mapping::MappingMethod::profile) {  // needs a surface
              edited.params.method =
                  cycle(mapping::kMappingMethodNames, edited.params.method, shift ? -1 : 1);
            }
            changed = true;
            break;
          case GLFW_KEY_N:
            edited.params.normalisation =
                cycle(mapping::kNormalisationNames, edited.params.normalisation, 1);
            changed = true;
            break;
          case GLFW_KEY_T:
            edited.params.strain = cycle(mapping::kStrainModeNames, edited.params.strain, 1);
            changed = true;
            break;
          case GLFW_KEY_Y:
            edited.layout = next_layout(edited.layout, shift ? -1 : 1);
            changed = true;
            break;
          case GLFW_KEY_G:
            edited.params.gain_um_per_strain =
                std::clamp(edited.params.gain_um_per_strain * (shift ? 0.5 : 2.0), 0.001, 1e6);
            changed = true;
            break;
          case GLFW_KEY_F:
            edited.params.peak_fraction = std::clamp(
                std::round(10 * edited.params.peak_fraction + (shift ? -1 : 1)) / 10, 0.1, 1.0);
            changed = true;
            break;
          case GLFW_KEY_E:
            edited.params.accumulate.reference_frame =
                std::max(-1, edited.params.accumulate.reference_frame + (shift ? -10 : 10));
            changed = true;
            break;
          case GLFW_KEY_R:
            edited.params.rate_hz = next_rate(edited, shown.get());
            changed = true;
            break;
          case GLFW_KEY_P:
            pin = true;
            break;
          case GLFW_KEY_TAB:
            toggle_ab = true;
            break;
          case GLFW_KEY_ENTER:
          case GLFW_KEY_KP_ENTER:
            audition_key = true;
            break;
          case GLFW_KEY_O:
            loop_audition = !loop_audition;
            break;
          case GLFW_KEY_S:
            save = true;
            break;
          case GLFW_KEY_H:
          case GLFW_KEY_F1:
            help_key = true;
            break;
          case GLFW_KEY_ESCAPE:
          case GLFW_KEY_Q:
            window.request_close();
            break;
          default:
            break;
        }
      }
    }
    if (help_key) help = !help;
    // The scrub bar, by mouse.
    if (shown && shown->error.empty() && ImGui::IsMouseDown(ImGuiMouseButton_Left) &&
        !io.WantCaptureMouse) {
      const ImVec2 p = io.MousePos;
      const double fx = p.x * fb_w / std::max(io.DisplaySize.x, 1.0f);
      const double fy = p.y * fb_h / std::max(io.DisplaySize.y, 1.0f);
      if (fy >= scrub_pane.y - 6 && fy < scrub_pane.y + scrub_pane.height + 6) {
        playing = false;
        position = display::scrub_frame(scrub_pane, fx, shown->movie.frame_count);
      }
    }
    if (changed) change(edited);
    if (pin && slot_b.outcome && slot_b.outcome->error.empty()) {
      slot_a = slot_b;
      a_mapper.reset();
      say(fmt::format("author: pinned A: {}", describe_request(slot_a->request)));
      status = "A pinned: change the mapping, Tab switches between A and B";
    }
    if (toggle_ab && slot_a) {
      show_a = !show_a;
      say(fmt::format("author: showing {}", show_a ? "A" : "B"));
    }
    if (audition_key) {
      if (audition.running()) {
        if (auto r = audition.stop()) result.auditions.push_back(*r);
      } else if (const auto chosen = shown_outcome(); chosen && chosen->error.empty()) {
        const auto& m = chosen->movie;
        movie::TactileMovie from_here = m;
        const auto n = static_cast<std::size_t>(m.layout.contactor_count());
        const std::int32_t from = std::clamp(frame, 0, std::max(m.frame_count - 1, 0));
        from_here.frame_count = m.frame_count - from;
        from_here.deflection_um.erase(
            from_here.deflection_um.begin(),
            from_here.deflection_um.begin() + static_cast<std::ptrdiff_t>(from * n));
        say(fmt::format("author: audition of {} from {:.3f} s{}", show_a ? "A" : "B",
                        from / m.rate_hz, loop_audition ? ", looped" : ""));
        audition.start(std::move(from_here), loop_audition ? kLoopedAuditionLoops : 1,
                       options.audition_backends, options.audition_latero, say);
      }
    }
    if (auto r = audition.finished()) result.auditions.push_back(*r);
    if (save) {
      try {
        const MappingOutcome* ao = slot_a && slot_a->outcome ? slot_a->outcome.get() : nullptr;
        if (!slot_b.outcome) throw std::invalid_argument("nothing mapped yet");
        result.saved =
            save_authoring(options.out_dir, options.name, options.strain_file, ao, *slot_b.outcome);
        status = fmt::format("saved {} and {} movie(s)", result.saved->experiment.string(),
                             result.saved->movies.size());
        for (const auto& m : result.saved->movies) say("author: saved " + m.string());
        say("author: saved " + result.saved->experiment.string());
      } catch (const std::exception& e) {
        status = std::string("save failed: ") + e.what();
        say("author: " + status);
      }
    }

    display::gl::render_imgui_frame();
    const Clock::time_point now_clock = Clock::now();
    if (result.frames_drawn == 0) first_frame = now_clock;
    ++result.frames_drawn;
    result.drawing_s = std::chrono::duration<double>(now_clock - first_frame).count();
    // Drawn this frame: B's mapping of the newest change.
    if (waiting_view && b_number >= asked && !show_a && shown == slot_b.outcome) {
      result.change_to_view_ms.push_back(ms_between(asked_at, now_clock));
      waiting_view = false;
    }
    const bool all_mapped = view_current && (!slot_a || slot_a->outcome);
    bool last = options.exit_after_frames >= 0 && result.frames_drawn >= options.exit_after_frames;
    if (options.screenshot && all_mapped) {
      // One more frame after everything is mapped, so that ImGui's layout has settled.
      if (screenshot_ready) {
        display::write_png(*options.screenshot, display::gl::read_pixels(fb_w, fb_h));
        say("author: wrote " + options.screenshot->string());
        last = true;
      }
      screenshot_ready = true;
    }
    glfwSwapBuffers(window.handle());
    if (last) break;
    glfwPollEvents();
    const double t = glfwGetTime();
    if (playing && shown && shown->error.empty()) {
      position += (t - last_t) * shown->movie.rate_hz;
      if (position >= shown->movie.frame_count) position = 0;
    }
    last_t = t;
  }
  if (auto r = audition.stop()) result.auditions.push_back(*r);
  result.current = slot_b.request;
  if (slot_a) result.a = slot_a->request;
  return result;
}

}  // namespace tactile::author
