// Movies to and from the formats other tools read (MPEG-I haptics HJIF, multichannel WAV).
// Argument order follows write_movie: the path first, then the movie.

#include <memory>
#include <optional>

#include "bindings.hpp"
#include "movies.hpp"
#include "tactile/movie/hjif.hpp"
#include "tactile/movie/wav.hpp"

namespace tactile::python {

void bind_exchange(py::module_& m) {
  using movie::TactileMovie;
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
        py::dict d;
        d["channels"] = s.channels;
        d["level"] = s.level;
        d["timescale"] = s.timescale;
        d["effects_per_channel"] = s.effects_per_channel;
        d["full_scale_um"] = s.full_scale_um;
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
