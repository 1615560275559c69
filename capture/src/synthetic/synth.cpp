#include "tactile/capture/synth.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "camera/cv_image.hpp"
#include "landmarks/fingerprint.hpp"
#include "synthetic/scene_model.hpp"
#include "tactile/capture/calibration_io.hpp"
#include "tactile/common/atomic_write.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/json.hpp"

namespace tactile::capture {

namespace {

// Mild vignetting plus a left-right gradient, as a prism and a single lamp give.
cv::Mat illumination_field(int width_px, int height_px) {
  cv::Mat field(height_px, width_px, CV_32F);
  const double cx = width_px * 0.55;
  const double cy = height_px * 0.45;
  const double r2max = cx * cx + cy * cy;
  for (int y = 0; y < height_px; ++y) {
    float* row = field.ptr<float>(y);
    for (int x = 0; x < width_px; ++x) {
      const double r2 = (x - cx) * (x - cx) + (y - cy) * (y - cy);
      row[x] = static_cast<float>((1.0 - 0.18 * r2 / r2max) * (0.95 + 0.08 * x / width_px));
    }
  }
  return field;
}

// Camera: illumination, optical blur, sensor noise, 8-bit quantisation.
GrayImage expose(const cv::Mat& reflectance, const cv::Mat& illumination, const SceneSpec& spec,
                 std::uint64_t noise_stream) {
  cv::Mat lit;
  if (spec.contrast != 1.0) {
    const cv::Mat faded = 0.9 - spec.contrast * (0.9 - reflectance);
    cv::multiply(faded, illumination, lit, 255.0);
  } else {
    cv::multiply(reflectance, illumination, lit, 255.0);
  }
  if (spec.blur_sigma_px > 0) cv::GaussianBlur(lit, lit, cv::Size(0, 0), spec.blur_sigma_px);
  if (spec.noise_sigma > 0) {
    cv::RNG rng(spec.seed * 0x9E3779B97F4A7C15ULL + noise_stream + 1);
    cv::Mat noise(lit.size(), CV_32F);
    rng.fill(noise, cv::RNG::NORMAL, 0.0, spec.noise_sigma);
    lit += noise;
  }
  cv::Mat out;
  lit.convertTo(out, CV_8U);  // rounds and saturates
  return from_mat(out);
}

GrayImage render_dot_grid(const SceneSpec& spec, const SceneModel& model,
                          const cv::Mat& illumination) {
  constexpr double kSpacing = 0.5;
  constexpr double kRadius = 0.1;
  constexpr double kOffsetX = 0.13;  // grid not aligned with the pixel lattice
  constexpr double kOffsetY = 0.21;
  constexpr int kSub = 4;
  cv::Mat reflectance(spec.height_px, spec.width_px, CV_32F);
  for (int y = 0; y < spec.height_px; ++y) {
    float* row = reflectance.ptr<float>(y);
    for (int x = 0; x < spec.width_px; ++x) {
      int inside = 0;
      for (int sy = 0; sy < kSub; ++sy) {
        for (int sx = 0; sx < kSub; ++sx) {
          const double xm = (x - 0.5 + (sx + 0.5) / kSub) * model.mm_per_px_x() - kOffsetX;
          const double ym = (y - 0.5 + (sy + 0.5) / kSub) * model.mm_per_px_y() - kOffsetY;
          const double dx = xm - kSpacing * std::round(xm / kSpacing);
          const double dy = ym - kSpacing * std::round(ym / kSpacing);
          inside += dx * dx + dy * dy < kRadius * kRadius ? 1 : 0;
        }
      }
      row[x] = static_cast<float>(0.85 - 0.65 * inside / double(kSub * kSub));
    }
  }
  return expose(reflectance, illumination, spec, 0xD07);
}

}  // namespace

void write_landmarks_csv(const std::filesystem::path& path,
                         const std::vector<TruthLandmark>& landmarks) {
  auto out = csv::open_with_header(path, "id,type,frame,x_px,y_px,x_mm,y_mm,diameter_mm");
  for (const auto& lm : landmarks) {
    out << fmt::format("{},{},{},{:.4f},{:.4f},{:.5f},{:.5f},{:.4f}\n", lm.id,
                       feature_type_name(lm.type), lm.frame, lm.x_px, lm.y_px, lm.x_mm, lm.y_mm,
                       lm.diameter_mm);
  }
  csv::finish(out, path);
}

SyntheticSequence render_sequence(const SceneSpec& spec,
                                  const std::function<void(int done, int total)>& progress) {
  const SceneModel model(spec);
  SyntheticSequence seq;
  seq.spec = spec;
  seq.calibration = true_calibration(spec);

  std::mt19937_64 rng(spec.seed);
  const double texels_per_mm = 2.0 / std::min(model.mm_per_px_x(), model.mm_per_px_y());
  const FingerprintTexture tex =
      render_fingerprint(spec, model.skin_min_x_mm(), model.skin_max_x_mm(), model.skin_min_y_mm(),
                         model.skin_max_y_mm(), texels_per_mm, rng);

  const int w = spec.width_px;
  const int h = spec.height_px;
  const cv::Mat illumination = illumination_field(w, h);
  seq.dot_grid = render_dot_grid(spec, model, illumination);

  // Static parts of the inverse map X = x - u(t) - p(t) d(x), in texel units.
  cv::Mat base_x(h, w, CV_32F), base_y(h, w, CV_32F), disp_x(h, w, CV_32F), disp_y(h, w, CV_32F);
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      const PointMm pos{x * model.mm_per_px_x(), y * model.mm_per_px_y()};
      const PointMm d = model.unit_displacement(pos);
      base_x.at<float>(y, x) = static_cast<float>((pos.x_mm - tex.origin_x_mm) * texels_per_mm);
      base_y.at<float>(y, x) = static_cast<float>((pos.y_mm - tex.origin_y_mm) * texels_per_mm);
      disp_x.at<float>(y, x) = static_cast<float>(-d.x_mm * texels_per_mm);
      disp_y.at<float>(y, x) = static_cast<float>(-d.y_mm * texels_per_mm);
    }
  }

  seq.frames.resize(static_cast<std::size_t>(spec.frame_count));
  const int batch = 16;
  for (int start = 0; start < spec.frame_count; start += batch) {
    const int end = std::min(spec.frame_count, start + batch);
    cv::parallel_for_(cv::Range(start, end), [&](const cv::Range& range) {
      for (int f = range.start; f < range.end; ++f) {
        cv::Mat map_x, map_y;
        if (model.is_sliding_scene()) {
          const PointMm u = model.slide(f);
          const double p = model.indentation(f);
          cv::scaleAdd(disp_x, p, base_x, map_x);
          cv::scaleAdd(disp_y, p, base_y, map_y);
          map_x -= u.x_mm * texels_per_mm;
          map_y -= u.y_mm * texels_per_mm;
        } else {
          // Partial slip is not a scaled static field: map every pixel through the model.
          map_x.create(h, w, CV_32F);
          map_y.create(h, w, CV_32F);
          for (int y = 0; y < h; ++y) {
            for (int x = 0; x < w; ++x) {
              const PointMm skin =
                  model.to_skin({x * model.mm_per_px_x(), y * model.mm_per_px_y()}, f);
              map_x.at<float>(y, x) =
                  static_cast<float>((skin.x_mm - tex.origin_x_mm) * texels_per_mm);
              map_y.at<float>(y, x) =
                  static_cast<float>((skin.y_mm - tex.origin_y_mm) * texels_per_mm);
            }
          }
        }
        cv::Mat print;
        cv::remap(tex.reflectance, print, map_x, map_y, cv::INTER_LINEAR, cv::BORDER_REPLICATE);
        // Skin out of contact reflects totally: bright, no ridges.
        for (int y = 0; y < h; ++y) {
          float* row = print.ptr<float>(y);
          for (int x = 0; x < w; ++x) {
            const double c = model.contact({x * model.mm_per_px_x(), y * model.mm_per_px_y()}, f);
            if (c < 1.0) row[x] = static_cast<float>(c * row[x] + (1 - c) * 0.9);
          }
        }
        seq.frames[static_cast<std::size_t>(f)] =
            expose(print, illumination, spec, static_cast<std::uint64_t>(f));
      }
    });
    if (progress) progress(end, spec.frame_count);
  }

  // Ground truth: every landmark in view and in contact, every frame.
  for (int f = 0; f < spec.frame_count; ++f) {
    for (const auto& lm : tex.landmarks) {
      const PointMm x = model.to_image(lm.skin, f);
      const double x_px = x.x_mm / model.mm_per_px_x();
      const double y_px = x.y_mm / model.mm_per_px_y();
      if (x_px < 0 || y_px < 0 || x_px > w - 1 || y_px > h - 1) continue;
      if (model.contact(x, f) < 0.5) continue;
      seq.landmarks.push_back({lm.id, lm.type, f, x_px, y_px, x.x_mm, x.y_mm, lm.diameter_mm});
    }
  }
  return seq;
}

void write_sequence(const std::filesystem::path& dir, const SyntheticSequence& sequence,
                    const std::string& command_line) {
  write_frames(dir, sequence.frames);
  // The dot grid goes in its own folder so that `tactile capture DIR` sees only the frames.
  std::filesystem::create_directories(dir / "calibration");
  write_png(dir / "calibration" / "dot_grid.png", sequence.dot_grid);

  write_landmarks_csv(dir / "landmarks.csv", sequence.landmarks);

  const SceneSpec& s = sequence.spec;
  nlohmann::json j;
  j["format"] = "tactile-synthetic-scene";
  j["format_version"] = 1;
  j["spec"] = {{"scene", to_string(s.scene)},
               {"speed_mm_per_s", s.speed_mm_per_s},
               {"feature_height_mm", s.feature_height_mm},
               {"feature_width_mm", s.feature_width_mm},
               {"frame_count", s.frame_count},
               {"frame_rate_hz", s.frame_rate_hz},
               {"width_px", s.width_px},
               {"height_px", s.height_px},
               {"field_width_mm", s.field_width_mm},
               {"field_height_mm", s.field_height_mm},
               {"contact_semi_x_mm", s.contact_semi_x_mm},
               {"contact_semi_y_mm", s.contact_semi_y_mm},
               {"displacement_per_height", s.displacement_per_height},
               {"ridge_period_mm", s.ridge_period_mm},
               {"pore_spacing_mm", s.pore_spacing_mm},
               {"pore_min_diameter_mm", s.pore_min_diameter_mm},
               {"pore_max_diameter_mm", s.pore_max_diameter_mm},
               {"minutiae_per_mm2", s.minutiae_per_mm2},
               {"blur_sigma_px", s.blur_sigma_px},
               {"noise_sigma", s.noise_sigma},
               {"contrast", s.contrast},
               {"rotation_deg", s.rotation_deg},
               {"lateral_amplitude_mm", s.lateral_amplitude_mm},
               {"stick_ratio", s.stick_ratio},
               {"seed", s.seed}};
  Provenance provenance = make_provenance({}, "synthetic scene", j["spec"].dump());
  provenance.command_line = command_line;
  j["provenance"] = provenance_json(provenance);
  j["calibration"] = calibration_json(sequence.calibration);
  j["frames"] = frame_files_text(sequence.frames.size());
  j["dot_grid"] = "calibration/dot_grid.png";
  const auto json_path = dir / "scene.json";
  write_text_atomically(json_path, j.dump(2) + "\n");
}

}  // namespace tactile::capture
