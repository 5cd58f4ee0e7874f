// cinepath lens: a depth-of-field calculator for camera operators (docs/lens.md).
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/parse_values.h"
#include "core/error.h"
#include "core/file_io.h"
#include "core/json.h"
#include "core/number_format.h"
#include "core/optics.h"
#include "core/version.h"

namespace cinepath::cli {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

std::string Metres(double m) { return std::isinf(m) ? "infinity" : FormatFixed(m, 2) + " m"; }

class LensCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("--focal-mm", focal_length_mm_, "Focal length, mm")->required();
    app.add_option("--f-number", f_number_, "Aperture as an f-number (2.8 for f/2.8)")->required();
    app.add_option("--focus-m", focus_text_, "Focus distance, metres, or 'inf'")->required();
    auto* sensor = app.add_option("--sensor", sensor_name_, "Filmback preset: " + PresetNames() + " (default super35)");
    auto* sensor_mm = app.add_option("--sensor-mm", sensor_mm_text_, "Sensor size WxH in mm, e.g. 36x24");
    sensor->excludes(sensor_mm);
    app.add_option("--width-px", width_px_, "Image width in pixels (default 3840)");
    app.add_option("--height-px", height_px_,
                   "Image height in pixels (default 2160); the image spans the sensor width and "
                   "width x H/W of its height (sensor fit, docs/optics.md)");
    app.add_option("--coc-mm", coc_mm_,
                   "Acceptable blur on the sensor, mm (default: 0.03 mm scaled by the sensor "
                   "diagonal relative to full frame)");
    app.add_option("--at-m", at_text_, "Report the blur at this subject distance (repeatable)");
    app.add_flag("--json", json_, "Print a JSON report instead of text");
    app.add_option("-o,--output", output_, "Write the report to a file ('-' = stdout, default)");
  }

  int Run() override {
    ValidateFocalLengthMm(focal_length_mm_, "--focal-mm");
    ValidateFNumber(f_number_, "--f-number");
    const double focus_m = ParseMetresOrInfinity(focus_text_, "--focus-m");
    ValidateFocusDistanceM(focus_m, focal_length_mm_, "--focus-m");

    Filmback filmback = {"super35", "Super 35", 24.89, 18.67};
    if (!sensor_name_.empty()) {
      auto preset = FindFilmback(sensor_name_);
      if (!preset) {
        throw InputError("--sensor: unknown filmback '" + sensor_name_ + "' (known: " + PresetNames() + ")");
      }
      filmback = *preset;
    } else if (!sensor_mm_text_.empty()) {
      const auto [w, h] = ParseSizeMm(sensor_mm_text_, "--sensor-mm");
      filmback = {"custom", "custom", w, h};
    }
    if (width_px_ <= 0) throw InputError("--width-px: must be > 0, got " + std::to_string(width_px_));
    if (height_px_ <= 0) throw InputError("--height-px: must be > 0, got " + std::to_string(height_px_));
    const ImageExtentMm image = ImageExtentOnSensorMm(filmback.width_mm, width_px_, height_px_);
    const bool coc_given = coc_mm_ >= 0;
    const double coc_mm = coc_given ? coc_mm_ : DefaultCocMm(filmback.width_mm, filmback.height_mm);
    if (coc_given && !(coc_mm > 0 && std::isfinite(coc_mm))) {
      throw InputError("--coc-mm: must be > 0");
    }
    std::vector<double> at_m;
    for (const auto& t : at_text_) {
      const double d = ParseMetresOrInfinity(t, "--at-m");
      if (!(d * 1000.0 > focal_length_mm_)) {
        throw InputError("--at-m: " + t + " m is not beyond the focal length " + FormatSignificant(focal_length_mm_) +
                         " mm");
      }
      at_m.push_back(d);
    }

    const DepthOfField dof = DepthOfFieldLimits(focal_length_mm_, f_number_, focus_m, coc_mm);
    const double hfov_deg = FieldOfViewRad(image.width_mm, focal_length_mm_) * 180.0 / M_PI;
    const double vfov_deg = FieldOfViewRad(image.height_mm, focal_length_mm_) * 180.0 / M_PI;
    struct Blur {
      double distance_m, coc_mm, coc_px;
    };
    std::vector<Blur> blur;
    for (double d : at_m) {
      const double c = BlurCircleMm(focal_length_mm_, f_number_, focus_m, d);
      blur.push_back({d, c, MmToPixels(c, filmback.width_mm, width_px_)});
    }

    std::string report;
    if (json_) {
      auto num = [](double v, int decimals) -> Json {
        if (std::isinf(v)) return nullptr;
        return RoundToDecimals(v, decimals);
      };
      Json j;
      j["schema"] = "cinepath.lens/1";
      j["focal_length_mm"] = num(focal_length_mm_, 6);
      j["f_number"] = num(f_number_, 6);
      j["focus_distance_m"] = num(focus_m, 6);
      j["sensor"] = {{"name", filmback.name},
                     {"width_mm", num(filmback.width_mm, 6)},
                     {"height_mm", num(filmback.height_mm, 6)},
                     {"width_px", width_px_},
                     {"height_px", height_px_},
                     {"image_height_mm", num(image.height_mm, 6)}};
      j["coc_limit_mm"] = num(coc_mm, 6);
      j["hyperfocal_m"] = num(dof.hyperfocal_m, 6);
      j["near_m"] = num(dof.near_m, 6);
      j["far_m"] = num(dof.far_m, 6);
      j["hfov_deg"] = num(hfov_deg, 6);
      j["vfov_deg"] = num(vfov_deg, 6);
      j["blur"] = Json::array();
      for (const auto& b : blur) {
        j["blur"].push_back(
            {{"distance_m", num(b.distance_m, 6)}, {"coc_mm", num(b.coc_mm, 6)}, {"coc_px", num(b.coc_px, 3)}});
      }
      report = DumpJson(j);
    } else {
      report += "lens        " + FormatSignificant(focal_length_mm_) + " mm at f/" + FormatSignificant(f_number_) +
                ", focused at " + (std::isinf(focus_m) ? std::string("infinity") : FormatSignificant(focus_m) + " m") +
                "\n";
      report += "sensor      " + filmback.label + " " + FormatSignificant(filmback.width_mm) + " x " +
                FormatSignificant(filmback.height_mm) + " mm, image " + std::to_string(width_px_) + " x " +
                std::to_string(height_px_) + " px on " + FormatSignificant(image.width_mm) + " x " +
                FormatFixed(image.height_mm, 2) + " mm\n";
      report += "blur limit  " + FormatFixed(coc_mm, 4) + " mm (" +
                FormatFixed(MmToPixels(coc_mm, filmback.width_mm, width_px_), 2) + " px)" +
                (coc_given ? "" : ", from the sensor diagonal") + "\n";
      report += "hyperfocal  " + Metres(dof.hyperfocal_m) + "\n";
      report += "near limit  " + Metres(dof.near_m) + "\n";
      report += "far limit   " + Metres(dof.far_m) + "\n";
      report +=
          "depth       " + (std::isinf(dof.far_m) ? std::string("infinity") : Metres(dof.far_m - dof.near_m)) + "\n";
      report += "field       " + FormatFixed(hfov_deg, 2) + " deg horizontal, " + FormatFixed(vfov_deg, 2) +
                " deg vertical\n";
      for (const auto& b : blur) {
        report += "blur at " +
                  (std::isinf(b.distance_m) ? std::string("infinity") : FormatSignificant(b.distance_m) + " m") + ": " +
                  FormatFixed(b.coc_mm, 4) + " mm, " + FormatFixed(b.coc_px, 1) + " px\n";
      }
    }
    WriteFileAtomic(output_, report);
    return 0;
  }

 private:
  static std::string PresetNames() {
    std::string names;
    for (const auto& f : FilmbackPresets()) names += (names.empty() ? "" : ", ") + f.name;
    return names;
  }

  double focal_length_mm_ = 0;
  double f_number_ = 0;
  std::string focus_text_;
  std::string sensor_name_;
  std::string sensor_mm_text_;
  int width_px_ = 3840;
  int height_px_ = 2160;
  double coc_mm_ = -1;
  std::vector<std::string> at_text_;
  bool json_ = false;
  std::string output_ = "-";
};

}  // namespace

std::unique_ptr<Command> MakeLensCommand() { return std::make_unique<LensCommand>(); }

}  // namespace cinepath::cli
