// ARFF export (see arff.hpp).

#include "tactile/perception/arff.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "tactile/common/atomic_write.hpp"

namespace tactile::perception {

void write_arff(const std::filesystem::path& path, const PerceptionDataset& d,
                const std::vector<std::size_t>& samples, const std::vector<std::size_t>& columns,
                ArffTarget target) {
  AtomicOstream out(path);
  out << "@relation perception\n\n";
  for (std::size_t c : columns) out << fmt::format("@attribute '{}' numeric\n", d.names.at(c));
  out << (target == ArffTarget::curvature ? "@attribute curvature {planar,conical,spherical}\n"
                                          : "@attribute footprint_mm numeric\n");
  out << "\n@data\n";
  constexpr const char* kNames[3] = {"planar", "conical", "spherical"};
  for (std::size_t i : samples) {
    const auto& s = d.samples.at(i);
    // 17 significant digits: WEKA reads exactly the doubles we train on.
    for (std::size_t c : columns) out << fmt::format("{:.17g},", s.inputs.at(c));
    if (target == ArffTarget::curvature)
      out << kNames[s.curvature] << '\n';
    else
      out << fmt::format("{:g}\n", s.footprint_mm);
  }
  out.commit();
}

}  // namespace tactile::perception
