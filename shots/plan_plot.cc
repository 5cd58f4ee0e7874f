#include "shots/plan_plot.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "core/error.h"
#include "core/number_format.h"
#include "core/optics.h"

namespace cinepath::shots {
namespace {

const char* const kPalette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                "#8c564b", "#e377c2", "#17becf", "#bcbd22", "#7f7f7f"};

std::string F(double v) { return FormatFixed(std::fabs(v) < 0.005 ? 0.0 : v, 2); }

std::string Escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<')
      out += "&lt;";
    else if (c == '>')
      out += "&gt;";
    else if (c == '&')
      out += "&amp;";
    else if (c == '"')
      out += "&quot;";
    else
      out += c;
  }
  return out;
}

// Maps a data box into a pixel box (y up in data, down in pixels), keeping the aspect ratio when asked.
struct Frame {
  double x0, y0, w, h;                // pixel box
  double min_x, max_x, min_y, max_y;  // data box
  double PX(double x) const { return x0 + (x - min_x) / (max_x - min_x) * w; }
  double PY(double y) const { return y0 + h - (y - min_y) / (max_y - min_y) * h; }
};

Frame MakeFrame(double x0, double y0, double w, double h, double min_x, double max_x, double min_y, double max_y,
                bool equal_aspect) {
  if (!(max_x > min_x)) min_x -= 1, max_x += 1;
  if (!(max_y > min_y)) min_y -= 1, max_y += 1;
  const double pad_x = 0.06 * (max_x - min_x), pad_y = 0.06 * (max_y - min_y);
  min_x -= pad_x, max_x += pad_x, min_y -= pad_y, max_y += pad_y;
  if (equal_aspect) {
    const double sx = (max_x - min_x) / w, sy = (max_y - min_y) / h;
    if (sx > sy) {
      const double extra = (sx * h - (max_y - min_y)) / 2;
      min_y -= extra, max_y += extra;
    } else {
      const double extra = (sy * w - (max_x - min_x)) / 2;
      min_x -= extra, max_x += extra;
    }
  }
  return {x0, y0, w, h, min_x, max_x, min_y, max_y};
}

void Panel(std::string& svg, const Frame& f, const std::string& title, const std::string& x_label,
           const std::string& y_label, bool show_y_range = true) {
  svg += "<rect x=\"" + F(f.x0) + "\" y=\"" + F(f.y0) + "\" width=\"" + F(f.w) + "\" height=\"" + F(f.h) +
         "\" fill=\"#fafafa\" stroke=\"#999\"/>\n";
  svg += "<text x=\"" + F(f.x0) + "\" y=\"" + F(f.y0 - 8) + "\" font-weight=\"bold\">" + Escape(title) + "</text>\n";
  svg += "<text x=\"" + F(f.x0 + f.w) + "\" y=\"" + F(f.y0 + f.h + 16) + "\" text-anchor=\"end\">" + Escape(x_label) +
         " [" + F(f.min_x) + " .. " + F(f.max_x) + "]</text>\n";
  svg += "<text x=\"" + F(f.x0 + 4) + "\" y=\"" + F(f.y0 + 14) + "\" fill=\"#555\">" + Escape(y_label) +
         (show_y_range ? " [" + F(f.min_y) + " .. " + F(f.max_y) + "]" : "") + "</text>\n";
}

template <typename GetX, typename GetY>
std::string Polyline(const Frame& f, size_t begin, size_t end, GetX gx, GetY gy, const std::string& style) {
  std::string pts;
  const size_t step = std::max<size_t>(1, (end - begin) / 2000);  // at most ~2000 points per line
  for (size_t i = begin; i < end; i += step) {
    pts += F(f.PX(gx(i))) + "," + F(f.PY(gy(i))) + " ";
  }
  if (end > begin) pts += F(f.PX(gx(end - 1))) + "," + F(f.PY(gy(end - 1)));
  return "<polyline fill=\"none\" " + style + " points=\"" + pts + "\"/>\n";
}

// The frame's horizontal field of view in the top view and its vertical one in the side view, as
// wedges `length_m` long from the camera.
std::string FrustumWedges(const TrajectorySample& s, const ImageExtentMm& image, double length_m, const Frame& top,
                          const Frame& side, const std::string& colour, const char* opacity) {
  const double hh = std::tan(FieldOfViewRad(image.width_mm, s.focal_length_mm) / 2);
  const double vh = std::tan(FieldOfViewRad(image.height_mm, s.focal_length_mm) / 2);
  const Eigen::Vector3d c = s.position_enu_m;
  auto corner = [&](double x, double y) {
    return Eigen::Vector3d(c + length_m * (s.world_from_camera * Eigen::Vector3d(x, y, 1.0)));
  };
  const Eigen::Vector3d l = corner(-hh, 0), r = corner(hh, 0), u = corner(0, -vh), d = corner(0, vh);
  const std::string style = "<polygon fill=\"" + colour + "\" fill-opacity=\"" + opacity + "\" stroke=\"" + colour;
  return style + "\" points=\"" + F(top.PX(c.x())) + "," + F(top.PY(c.y())) + " " + F(top.PX(l.x())) + "," +
         F(top.PY(l.y())) + " " + F(top.PX(r.x())) + "," + F(top.PY(r.y())) + "\"/>\n" + style + "\" points=\"" +
         F(side.PX(c.x())) + "," + F(side.PY(c.z())) + " " + F(side.PX(u.x())) + "," + F(side.PY(u.z())) + " " +
         F(side.PX(d.x())) + "," + F(side.PY(d.z())) + "\"/>\n";
}

// The document, its background and, for a plan with no samples, its only line.
std::string SvgStart(double width, double height) {
  std::string svg = "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  svg += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + F(width) + "\" height=\"" + F(height) +
         "\" viewBox=\"0 0 " + F(width) + " " + F(height) + "\" font-family=\"sans-serif\" font-size=\"12\">\n";
  svg += "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  return svg;
}

// What the views span (every flight, home and subject), the longest flight's end, and the subjects, each
// once (they are the scene's, shared by every flight: the first flight that has each).
struct Extents {
  double min_e = std::numeric_limits<double>::infinity(), max_e = -min_e, min_n = min_e, max_n = -min_e, min_u = min_e,
         max_u = -min_e, t_end = 0;
  std::vector<const SubjectTrack*> subjects;
  void Grow(const Eigen::Vector3d& p) {
    min_e = std::min(min_e, p.x()), max_e = std::max(max_e, p.x());
    min_n = std::min(min_n, p.y()), max_n = std::max(max_n, p.y());
    min_u = std::min(min_u, p.z()), max_u = std::max(max_u, p.z());
  }
};

Extents ExtentsOf(const TeamPlan& plan) {
  Extents x;
  for (const auto& flight : plan.flights) {
    for (const auto& s : flight.plan.samples) x.Grow(s.position_enu_m);
    if (flight.home_enu_m) x.Grow(*flight.home_enu_m);
    if (!flight.plan.samples.empty()) x.t_end = std::max(x.t_end, flight.plan.samples.back().time_s);
  }
  for (const auto& flight : plan.flights) {
    for (const auto& subj : flight.plan.subjects) {
      bool seen = false;
      for (const SubjectTrack* other : x.subjects) seen = seen || other->name == subj.name;
      if (seen) continue;
      x.subjects.push_back(&subj);
      for (const auto& p : subj.positions_enu_m) {
        x.Grow(p);
        x.Grow(p + Eigen::Vector3d(0, 0, subj.height_m));
      }
    }
  }
  return x;
}

// A subject where it stands at its sample i: a dot from above, a bar of its height from the side.
std::string SubjectMarker(const SubjectTrack& subj, size_t i, const Frame& top, const Frame& side) {
  const Eigen::Vector3d& p = subj.positions_enu_m[i];
  return "<circle cx=\"" + F(top.PX(p.x())) + "\" cy=\"" + F(top.PY(p.y())) + "\" r=\"3\" fill=\"#555\"/>\n" +
         "<line x1=\"" + F(side.PX(p.x())) + "\" y1=\"" + F(side.PY(p.z())) + "\" x2=\"" + F(side.PX(p.x())) +
         "\" y2=\"" + F(side.PY(p.z() + subj.height_m)) + "\" stroke=\"#555\" stroke-width=\"3\"/>\n";
}

// A subject's path in both views and its name at its start.
void DrawSubjectPath(std::string& svg, const SubjectTrack& subj, const Frame& top, const Frame& side) {
  const auto& P = subj.positions_enu_m;
  svg += Polyline(
      top, 0, P.size(), [&](size_t i) { return P[i].x(); }, [&](size_t i) { return P[i].y(); },
      "stroke=\"#999\" stroke-width=\"2\" stroke-dasharray=\"4 3\"");
  svg += Polyline(
      side, 0, P.size(), [&](size_t i) { return P[i].x(); }, [&](size_t i) { return P[i].z(); },
      "stroke=\"#999\" stroke-width=\"2\" stroke-dasharray=\"4 3\"");
  svg += "<text x=\"" + F(top.PX(P.front().x()) + 5) + "\" y=\"" + F(top.PY(P.front().y()) - 5) + "\" fill=\"#555\">" +
         Escape(subj.name) + "</text>\n";
}

// Each sample's shot index (into plan.shots).
std::vector<size_t> ShotOfSamples(const Trajectory& plan) {
  std::vector<size_t> shot_of(plan.samples.size(), 0);
  for (size_t i = 0; i < plan.samples.size(); ++i) {
    for (size_t k = 0; k < plan.shots.size(); ++k) {
      if (plan.shots[k].name == plan.samples[i].shot) shot_of[i] = k;
    }
  }
  return shot_of;
}

// One drone's flight, one polyline per shot in the shot's colour (a version 1 plan's picture).
void DrawShotsOfFlight(std::string& svg, const Trajectory& plan, const std::vector<size_t>& shot_of, const Frame& top,
                       const Frame& side) {
  const auto& S = plan.samples;
  size_t begin = 0;
  for (size_t i = 1; i <= S.size(); ++i) {
    if (i == S.size() || shot_of[i] != shot_of[begin]) {
      const std::string colour = kPalette[shot_of[begin] % 10];
      const std::string style = "stroke=\"" + colour + "\" stroke-width=\"2\"";
      svg += Polyline(
          top, begin, i, [&](size_t k) { return S[k].position_enu_m.x(); },
          [&](size_t k) { return S[k].position_enu_m.y(); }, style);
      svg += Polyline(
          side, begin, i, [&](size_t k) { return S[k].position_enu_m.x(); },
          [&](size_t k) { return S[k].position_enu_m.z(); }, style);
      begin = i;
    }
  }
}

// One drone of several in its own colour: one path per view, lifted at the drone's cuts (a "cut"
// transition: it does not fly there); its name at its first sample, its home as a square.
void DrawDroneOfTeam(std::string& svg, const DroneFlight& flight, const std::string& colour, const Frame& top,
                     const Frame& side) {
  const auto& S = flight.plan.samples;
  const std::string style =
      "class=\"flight\" data-drone=\"" + Escape(flight.name) + "\" stroke=\"" + colour + "\" stroke-width=\"2.5\"";
  std::vector<size_t> runs = {0};
  for (size_t i = 1; i < S.size(); ++i) {
    if (S[i].shot == S[i - 1].shot) continue;
    for (const auto& shot : flight.plan.shots) {
      if (shot.name == S[i].shot && shot.transition == "cut") runs.push_back(i);
    }
  }
  runs.push_back(S.size());
  for (const Frame* view : {&top, &side}) {
    std::string d;
    for (size_t r = 0; r + 1 < runs.size(); ++r) {
      const size_t begin = runs[r], end = runs[r + 1];
      const size_t step = std::max<size_t>(1, (end - begin) / 1000);
      for (size_t i = begin; i < end; i += step) {
        const Eigen::Vector3d& p = S[i].position_enu_m;
        d += (i == begin ? "M" : " L") + F(view->PX(p.x())) + "," + F(view->PY(view == &top ? p.y() : p.z()));
      }
      const Eigen::Vector3d& p = S[end - 1].position_enu_m;
      d += " L" + F(view->PX(p.x())) + "," + F(view->PY(view == &top ? p.y() : p.z())) + " ";
    }
    svg += "<path fill=\"none\" " + style + " d=\"" + d + "\"/>\n";
  }
  svg += "<text x=\"" + F(top.PX(S.front().position_enu_m.x()) + 6) + "\" y=\"" +
         F(top.PY(S.front().position_enu_m.y()) + 14) + "\" fill=\"" + colour + "\" font-weight=\"bold\">" +
         Escape(flight.name) + "</text>\n";
  if (flight.home_enu_m) {
    const Eigen::Vector3d& h = *flight.home_enu_m;
    svg += "<rect x=\"" + F(top.PX(h.x()) - 5) + "\" y=\"" + F(top.PY(h.y()) - 5) +
           "\" width=\"10\" height=\"10\" fill=\"white\" stroke=\"" + colour + "\" stroke-width=\"2\"/>\n";
    svg += "<rect x=\"" + F(side.PX(h.x()) - 5) + "\" y=\"" + F(side.PY(h.z()) - 5) +
           "\" width=\"10\" height=\"10\" fill=\"white\" stroke=\"" + colour + "\" stroke-width=\"2\"/>\n";
  }
}

// One flight in the top and side views, with its frustums every `stride` samples. A version 1 plan's
// flight is coloured by shot, with its subjects where they stand at each frustum; a team's by drone.
void DrawFlight(std::string& svg, const TeamPlan& plan, size_t k, const Frame& top, const Frame& side,
                double frustum_len, size_t stride) {
  const DroneFlight& flight = plan.flights[k];
  const auto& S = flight.plan.samples;
  if (S.empty()) return;
  const std::vector<size_t> shot_of = plan.single ? ShotOfSamples(flight.plan) : std::vector<size_t>();
  if (plan.single) {
    DrawShotsOfFlight(svg, flight.plan, shot_of, top, side);
  } else {
    DrawDroneOfTeam(svg, flight, kPalette[k % 10], top, side);
  }
  const ImageExtentMm image = flight.plan.camera.image_extent_mm();
  for (size_t i = 0; i < S.size(); i += stride) {
    const std::string colour = kPalette[(plan.single ? shot_of[i] : k) % 10];
    svg += FrustumWedges(S[i], image, frustum_len, top, side, colour, plan.single ? "0.15" : "0.12");
    if (!plan.single) continue;
    for (const auto& subj : flight.plan.subjects) svg += SubjectMarker(subj, i, top, side);
  }
}

// The lens against time: focal length (log) and focus (dioptres).
void DrawLensCurves(std::string& svg, const Trajectory& plan, const Frame& focal, const Frame& focus,
                    const std::string& focal_style, const std::string& focus_style) {
  const auto& S = plan.samples;
  svg += Polyline(
      focal, 0, S.size(), [&](size_t i) { return S[i].time_s; },
      [&](size_t i) { return std::log(S[i].focal_length_mm); }, focal_style);
  svg += Polyline(
      focus, 0, S.size(), [&](size_t i) { return S[i].time_s; },
      [&](size_t i) { return std::isfinite(S[i].focus_distance_m) ? 1.0 / S[i].focus_distance_m : 0.0; }, focus_style);
}

// A version 1 plan's time panels: focal length, focus and f-number with shot boundaries and broken-limit
// time ranges shaded red; the legend names the shots.
void DrawShotTimePanels(std::string& svg, const Trajectory& plan, double t_max, double height) {
  const auto& S = plan.samples;
  double f_min = std::numeric_limits<double>::infinity(), f_max = 0, dio_max = 0, n_min = f_min, n_max = 0;
  for (const auto& s : S) {
    f_min = std::min(f_min, s.focal_length_mm), f_max = std::max(f_max, s.focal_length_mm);
    if (std::isfinite(s.focus_distance_m)) dio_max = std::max(dio_max, 1.0 / s.focus_distance_m);
    n_min = std::min(n_min, s.f_number), n_max = std::max(n_max, s.f_number);
  }
  const Frame focal = MakeFrame(40, 590, 1130, 100, 0, t_max, std::log(f_min), std::log(f_max), false);
  const Frame focus = MakeFrame(40, 730, 1130, 90, 0, t_max, 0, std::max(dio_max, 1e-3), false);
  const Frame fnum = MakeFrame(40, 860, 1130, 80, 0, t_max, n_min, n_max, false);
  Panel(svg, focal, "Focal length (log scale)", "time s", "focal mm " + F(f_min) + " .. " + F(f_max), false);
  Panel(svg, focus, "Focus (dioptres; 0 = infinity)", "time s", "1/m");
  Panel(svg, fnum, "Aperture", "time s", "f-number");
  for (const Frame* fr : {&focal, &focus, &fnum}) {
    for (const auto& shot : plan.shots) {
      svg += "<line x1=\"" + F(fr->PX(shot.start_time_s)) + "\" y1=\"" + F(fr->y0) + "\" x2=\"" +
             F(fr->PX(shot.start_time_s)) + "\" y2=\"" + F(fr->y0 + fr->h) + "\" stroke=\"#ccc\"/>\n";
    }
    for (const auto& v : plan.feasibility.violations) {
      const double x0 = fr->PX(v.start_time_s), x1 = std::max(fr->PX(v.end_time_s), x0 + 1);
      svg += "<rect x=\"" + F(x0) + "\" y=\"" + F(fr->y0) + "\" width=\"" + F(x1 - x0) + "\" height=\"" + F(fr->h) +
             "\" fill=\"red\" fill-opacity=\"0.12\"/>\n";
    }
  }
  DrawLensCurves(svg, plan, focal, focus, "stroke=\"#1f77b4\" stroke-width=\"2\"",
                 "stroke=\"#2ca02c\" stroke-width=\"2\"");
  svg += Polyline(
      fnum, 0, S.size(), [&](size_t i) { return S[i].time_s; }, [&](size_t i) { return S[i].f_number; },
      "stroke=\"#9467bd\" stroke-width=\"2\"");
  // Legend.
  double lx = 40;
  for (size_t k = 0; k < plan.shots.size(); ++k) {
    const std::string label = plan.shots[k].name + " (" + plan.shots[k].type + ")";
    svg += "<rect x=\"" + F(lx) + "\" y=\"" + F(height - 18) + "\" width=\"10\" height=\"10\" fill=\"" +
           kPalette[k % 10] + "\"/>\n";
    svg += "<text x=\"" + F(lx + 14) + "\" y=\"" + F(height - 9) + "\">" + Escape(label) + "</text>\n";
    lx += 24 + 7.0 * static_cast<double>(label.size());
  }
}

// A team's time panels: the edit (which camera is live) with the team's conflicts, then every drone's
// focal length and focus; the legend names the drones.
void DrawTeamTimePanels(std::string& svg, const TeamPlan& plan, double t_max, double height) {
  auto colour_of = [](size_t flight) { return std::string(kPalette[flight % 10]); };
  auto flight_colour = [&](const std::string& name) {
    const int k = plan.FindFlight(name);
    return k < 0 ? std::string("#555") : colour_of(static_cast<size_t>(k));
  };
  double f_min = std::numeric_limits<double>::infinity(), f_max = 0, dio_max = 0;
  for (const auto& flight : plan.flights) {
    for (const auto& s : flight.plan.samples) {
      f_min = std::min(f_min, s.focal_length_mm), f_max = std::max(f_max, s.focal_length_mm);
      if (std::isfinite(s.focus_distance_m)) dio_max = std::max(dio_max, 1.0 / s.focus_distance_m);
    }
  }
  const Frame team = MakeFrame(40, 590, 1130, 110, 0, t_max, 0, 1, false);
  // At least 2 % of focal length top to bottom, so rounding noise in a constant lens draws flat.
  const double log_mid = 0.5 * (std::log(f_min) + std::log(f_max));
  const double log_half = std::max(0.5 * (std::log(f_max) - std::log(f_min)), 0.01);
  const Frame focal = MakeFrame(40, 740, 1130, 90, 0, t_max, log_mid - log_half, log_mid + log_half, false);
  const Frame focus = MakeFrame(40, 870, 1130, 80, 0, t_max, 0, std::max(dio_max, 1e-3), false);
  const std::string team_title = "Team: the edit (live camera) and conflicts (separation < " +
                                 F(plan.team.min_separation_m) + " m in red, a drone in another's shot in orange): " +
                                 (plan.team.clear() ? std::string("none") : std::to_string(plan.team.conflicts.size()));
  Panel(svg, team, team_title, "time s", "", false);
  Panel(svg, focal, "Focal length (log scale)", "time s", "focal mm " + F(f_min) + " .. " + F(f_max), false);
  Panel(svg, focus, "Focus (dioptres; 0 = infinity)", "time s", "1/m");
  // The edit: a bar in the live drone's colour from each cut to the next (or the end).
  const double bar_y = team.y0 + 22, bar_h = 16;
  for (size_t c = 0; c < plan.edit.size(); ++c) {
    const EditCut& cut = plan.edit[c];
    const double end_s = c + 1 < plan.edit.size() ? plan.edit[c + 1].at_s : t_max;
    const double x0 = team.PX(cut.at_s), x1 = std::max(team.PX(end_s), x0 + 1);
    svg += "<rect class=\"edit\" data-drone=\"" + Escape(cut.drone) + "\" x=\"" + F(x0) + "\" y=\"" + F(bar_y) +
           "\" width=\"" + F(x1 - x0) + "\" height=\"" + F(bar_h) + "\" fill=\"" + flight_colour(cut.drone) +
           "\" fill-opacity=\"0.8\"/>\n";
    svg += "<text x=\"" + F(x0 + 3) + "\" y=\"" + F(bar_y + 12) + "\" fill=\"white\">" + Escape(cut.drone) +
           (cut.match_focus ? " (focus matched)" : "") + "</text>\n";
  }
  if (plan.edit.empty()) {
    svg += "<text x=\"" + F(team.x0 + 4) + "\" y=\"" + F(bar_y + 12) +
           "\" fill=\"#555\">no edit: every camera counts as live</text>\n";
  }
  // Conflicts: shaded over every time panel, labelled on the team panel (one row per conflict, wrapping).
  for (size_t c = 0; c < plan.team.conflicts.size(); ++c) {
    const TeamConflict& v = plan.team.conflicts[c];
    const std::string fill = v.limit == "separation" ? "red" : "orange";
    for (const Frame* fr : {&team, &focal, &focus}) {
      const double x0 = fr->PX(v.start_time_s), x1 = std::max(fr->PX(v.end_time_s), x0 + 2);
      svg += "<rect class=\"conflict\" data-limit=\"" + Escape(v.limit) + "\" x=\"" + F(x0) + "\" y=\"" + F(fr->y0) +
             "\" width=\"" + F(x1 - x0) + "\" height=\"" + F(fr->h) + "\" fill=\"" + fill +
             "\" fill-opacity=\"0.18\"/>\n";
    }
    const std::string label = v.limit == "separation"
                                  ? v.drone + "-" + v.other + " " + F(v.worst_value) + " m apart"
                                  : v.other + " in " + v.drone + "'s shot (" + F(v.worst_value) + " px)";
    const double row = static_cast<double>(c % 4);
    svg += "<text x=\"" + F(team.PX(v.start_time_s) + 2) + "\" y=\"" + F(bar_y + bar_h + 14 + 14 * row) + "\" fill=\"" +
           (v.limit == "separation" ? std::string("#b00") : std::string("#c60")) + "\">" + Escape(label) + "</text>\n";
  }
  // Every drone's broken limits: shaded red over the lens panels, each range named on the focal panel.
  size_t row = 0;
  for (const auto& flight : plan.flights) {
    for (const auto& v : flight.plan.feasibility.violations) {
      for (const Frame* fr : {&focal, &focus}) {
        const double x0 = fr->PX(v.start_time_s), x1 = std::max(fr->PX(v.end_time_s), x0 + 1);
        svg += "<rect class=\"violation\" data-drone=\"" + Escape(flight.name) + "\" data-limit=\"" + Escape(v.limit) +
               "\" x=\"" + F(x0) + "\" y=\"" + F(fr->y0) + "\" width=\"" + F(x1 - x0) + "\" height=\"" + F(fr->h) +
               "\" fill=\"red\" fill-opacity=\"0.12\"/>\n";
      }
      svg += "<text x=\"" + F(focal.PX(v.start_time_s) + 2) + "\" y=\"" + F(focal.y0 + 28 + 14 * double(row++ % 4)) +
             "\" fill=\"#b00\">" + Escape(flight.name + ": " + v.limit) + "</text>\n";
    }
  }
  for (size_t k = 0; k < plan.flights.size(); ++k) {
    const std::string style = "stroke=\"" + colour_of(k) + "\" stroke-width=\"2\"";
    DrawLensCurves(svg, plan.flights[k].plan, focal, focus, style, style);
  }
  // Legend: the drones by name, each with its shots and its broken limits.
  double lx = 40;
  for (size_t k = 0; k < plan.flights.size(); ++k) {
    const auto& flight = plan.flights[k];
    const size_t broken = flight.plan.feasibility.violations.size();
    std::string label =
        flight.name + " (" + flight.plan.drone.name + ", " + std::to_string(flight.plan.shots.size()) + " shot" +
        (flight.plan.shots.size() == 1 ? "" : "s") +
        (broken ? ", " + std::to_string(broken) + " broken limit range" + (broken == 1 ? "" : "s") : std::string()) +
        ")";
    svg += "<rect class=\"legend\" x=\"" + F(lx) + "\" y=\"" + F(height - 22) +
           "\" width=\"12\" height=\"12\" fill=\"" + colour_of(k) + "\"/>\n";
    svg += "<text x=\"" + F(lx + 16) + "\" y=\"" + F(height - 12) + "\">" + Escape(label) + "</text>\n";
    lx += 30 + 7.0 * static_cast<double>(label.size());
  }
}

}  // namespace

std::string PlanToSvg(const TeamPlan& plan) {
  const double width = 1200, height = plan.single ? 980 : 1000;
  std::string svg = SvgStart(width, height);
  if (plan.SampleCount() == 0) {
    svg += "<text x=\"20\" y=\"40\">empty plan</text>\n</svg>\n";
    return svg;
  }
  const Extents x = ExtentsOf(plan);
  const double extent = std::max({x.max_e - x.min_e, x.max_n - x.min_n, x.max_u - x.min_u, 1.0});
  const double frustum_len = 0.08 * extent;
  const Frame top = MakeFrame(40, 50, 540, 480, x.min_e, x.max_e, x.min_n, x.max_n, true);
  const Frame side = MakeFrame(630, 50, 540, 480, x.min_e, x.max_e, x.min_u, x.max_u, true);
  Panel(svg, top,
        plan.single ? std::string("Top-down (north up)")
                    : "Top-down (north up), " + std::to_string(plan.flights.size()) + " drones",
        "east m", "north m");
  Panel(svg, side, "Side (looking north)", "east m", "up m");
  for (const SubjectTrack* subj : x.subjects) {
    if (subj->positions_enu_m.empty()) continue;
    DrawSubjectPath(svg, *subj, top, side);
    if (!plan.single) svg += SubjectMarker(*subj, 0, top, side);
  }
  // Frustums every ~2 s (8..60 of them along the longest flight).
  const size_t count = std::clamp<size_t>(static_cast<size_t>(x.t_end / 2.0), 8, 60);
  const size_t stride = std::max<size_t>(1, plan.SampleCount() / count);
  for (size_t k = 0; k < plan.flights.size(); ++k) DrawFlight(svg, plan, k, top, side, frustum_len, stride);
  const double t_max = std::max(x.t_end, 1e-3);
  if (plan.single) {
    DrawShotTimePanels(svg, plan.flights.front().plan, t_max, height);
  } else {
    DrawTeamTimePanels(svg, plan, t_max, height);
  }
  svg += "</svg>\n";
  return svg;
}

std::string PlanToSvg(const Trajectory& plan) {
  TeamPlan one;
  one.single = true;
  one.origin = plan.origin;
  one.frame_rate_hz = plan.frame_rate_hz;
  one.flights.push_back({plan.drone.name, std::nullopt, plan});
  return PlanToSvg(one);
}

}  // namespace cinepath::shots
