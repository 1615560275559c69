#include "tactile/capture/pore_training.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "pores/pore_model.hpp"

namespace tactile::capture {

TrainedPoreModels train_pore_models(const std::vector<PoreTrainingPrint>& prints,
                                    const PoreTrainingSettings& settings, bool held_out,
                                    const std::function<void(int k, int n)>& progress) {
  if (prints.empty()) throw std::invalid_argument("pore model: no prints to train on");
  if (held_out && prints.size() < 2) {
    throw std::invalid_argument(fmt::format(
        "pore model: leaving one print out needs at least 2 prints, got {}", prints.size()));
  }
  // Candidates do not depend on the model, and finding them is most of the work: they are
  // labelled once and shared by every fold.
  const int n = static_cast<int>(prints.size());
  std::vector<LabelledCandidates> labelled;
  labelled.reserve(prints.size());
  for (int k = 0; k < n; ++k) {
    if (progress) progress(k + 1, n);
    labelled.push_back(label_pore_candidates(prints[static_cast<std::size_t>(k)],
                                             settings.px_per_mm, settings.params,
                                             settings.label_radius_mm));
  }
  const auto all_but = [&](std::size_t left_out) {
    std::vector<const LabelledCandidates*> sets;
    for (std::size_t j = 0; j < labelled.size(); ++j) {
      if (j != left_out) sets.push_back(&labelled[j]);
    }
    return fit_pore_model(sets, settings.l2);
  };
  TrainedPoreModels out;
  out.model = all_but(labelled.size());
  if (held_out) {
    for (std::size_t i = 0; i < labelled.size(); ++i) out.held_out.push_back(all_but(i));
  }
  return out;
}

}  // namespace tactile::capture
