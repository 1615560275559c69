// Movies to and from the formats other tools read (MPEG-I haptics HJIF, multichannel WAV).
// Argument order follows write_movie: the path first, then the movie.

#include <memory>
#include <optional>
#include <string>

#include "bindings.hpp"
#include "movies.hpp"
#include "request_kwargs.hpp"
#include "tactile/movie/export_request.hpp"
#include "tactile/movie/hjif.hpp"
#include "tactile/movie/wav.hpp"

namespace tactile::python {

namespace {

// export(movie, hjif=..., wav=...): the files `tactile export` writes, by the same run.
py::dict export_movie(const movie::TactileMovie& mv, const py::kwargs& kwargs) {
  movie::ExportRequest request;
  set_from_kwargs(request, movie::export_options(), kwargs, "export");
  movie::ExportSummary s;
  {
    py::gil_scoped_release unlocked;
    s = movie::run_export(request, mv, OptionSpelling::python);
  }
  py::dict d;
  if (s.hjif) {
    d["hjif_channels"] = s.hjif->channels;
    d["hjif_timescale"] = s.hjif->timescale;
    d["hjif_full_scale_um"] = s.hjif->full_scale_um;
  }
  if (s.wav_full_scale_um) d["wav_full_scale_um"] = *s.wav_full_scale_um;
  d["summary"] = s.lines;
  return d;
}

}  // namespace

void bind_exchange(py::module_& m) {
  using movie::TactileMovie;
  def_with_kwargs(
      m, "export", &export_movie, movie::export_options(),
      "Writes the movie in formats other tools read, as `tactile export`: every file given or\n"
      "none, atomically. Returns what was written (HJIF channels, timescale and the deflection\n"
      "written as amplitude 1; the WAV's full scale) and the summary lines. Keywords (the\n"
      "command line's options, with underscores):",
      py::arg("movie"));
  m.def(
      "export_hjif",
      [](const std::filesystem::path& path, const TactileMovie& mv, int ticks_per_sample) {
        movie::HjifOptions options;
        options.ticks_per_sample = ticks_per_sample;
        movie::HjifSummary s;
        {
          py::gil_scoped_release unlocked;
          s = movie::write_hjif(mv, path, options);
        }
        using S = movie::HjifSummary;
        py::dict d;
        put_fields(d, s, field("channels", &S::channels), field("level", &S::level),
                   field("timescale", &S::timescale),
                   field("effects_per_channel", &S::effects_per_channel),
                   field("full_scale_um", &S::full_scale_um));
        return d;
      },
      py::arg("path"), py::arg("movie"), py::arg("ticks_per_sample") = 1,
      "Writes the movie as MPEG-I Haptics JSON (.hjif), atomically; returns what was written "
      "(channels, level, timescale, effects per channel, the deflection written as amplitude "
      "1). The mapping, field by field: docs/formats.md.");
  m.def(
      "import_hjif",
      [](const std::filesystem::path& path, const std::optional<LayoutArgument>& layout) {
        movie::HjifImportOptions options;
        if (layout) options.layout = layout_argument(*layout);
        py::gil_scoped_release unlocked;
        return std::make_shared<TactileMovie>(
            with_inputs({path}, [&] { return movie::read_hjif(path, options); }));
      },
      py::arg("path"), py::arg("layout") = py::none(),
      "Reads an MPEG-I Haptics JSON file as a tactile movie; `layout` (a Layout, a built-in "
      "name or FILE.json) is needed when the file does not carry one.");
  m.def(
      "export_wav",
      [](const std::filesystem::path& path, const TactileMovie& mv) {
        py::gil_scoped_release unlocked;
        return movie::write_wav(mv, path);
      },
      py::arg("path"), py::arg("movie"),
      "Writes one float32 channel per contactor at the movie's rate, atomically; returns the "
      "deflection in um that a sample of 1.0 stands for.");
}

}  // namespace tactile::python
