// Classifier of labelled recordings: labels, inputs, model file, testing, cross-validation
// (see classifier_model.hpp).

#include "tactile/perception/classifier_model.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/csv.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/names.hpp"
#include "tactile/common/parallel_for.hpp"
#include "tactile/common/value_checks.hpp"
#include "tactile/perception/recording_csv.hpp"

namespace tactile::perception {
namespace {

std::string trim(std::string s) {
  const auto not_space = [](unsigned char c) { return !std::isspace(c); };
  s.erase(s.begin(), std::find_if(s.begin(), s.end(), not_space));
  s.erase(std::find_if(s.rbegin(), s.rend(), not_space).base(), s.end());
  return s;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  for (std::string f; std::getline(ss, f, ',');) fields.push_back(trim(f));
  if (!line.empty() && line.back() == ',') fields.emplace_back();
  return fields;
}

// A required field of `j`, of the JSON type `is` checks, or a FormatError naming the file.
const nlohmann::json& field(const nlohmann::json& j, const char* key, const std::string& where,
                            bool (nlohmann::json::*is)() const noexcept, const char* type) {
  const auto it = j.find(key);
  if (it == j.end()) throw FormatError(fmt::format("{}: missing field '{}'", where, key));
  if (!((*it).*is)()) throw FormatError(fmt::format("{}: field '{}' must be {}", where, key, type));
  return *it;
}

template <typename T>
std::vector<T> array_of(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& a = field(j, key, where, &nlohmann::json::is_array, "an array");
  try {
    return a.get<std::vector<T>>();
  } catch (const nlohmann::json::exception&) {
    throw FormatError(fmt::format("{}: field '{}' has an element of the wrong type", where, key));
  }
}

// The classifier is retrained from the stored rows when the model is loaded, so a damaged row
// changes every prediction without a sign: each input must be finite and of a size a sensor
// gives, and the stored scaler (written as the rows' own minimum and maximum) must still be
// theirs, which catches hand edits of either.
void check_training_rows(const ClassifierModel& m, const std::string& where) {
  constexpr double kMaxInput = 1e12;  // far beyond any mean, rate or band power of a 12-bit ADC
  for (std::size_t i = 0; i < m.rows.size(); ++i) {
    for (std::size_t k = 0; k < m.rows[i].size(); ++k) {
      const double v = m.rows[i][k];
      if (!std::isfinite(v) || std::abs(v) > kMaxInput)
        throw FormatError(
            fmt::format("{}: training row {} ({}): input {} = {} is not a finite "
                        "number within +-1e12",
                        where, i, m.files[i], m.input_names[k], v));
    }
  }
  for (std::size_t k = 0; k < m.input_names.size(); ++k) {
    double lo = m.rows.front()[k], hi = lo;
    for (const auto& row : m.rows) {
      lo = std::min(lo, row[k]);
      hi = std::max(hi, row[k]);
    }
    const auto same = [](double a, double b) {
      return std::abs(a - b) <= 1e-9 * std::max({1.0, std::abs(a), std::abs(b)});
    };
    if (!same(m.scaler.min[k], lo) || !same(m.scaler.max[k], hi))
      throw FormatError(fmt::format(
          "{}: scaler of input {} is [{}, {}] but its training rows span [{}, {}] (edited or "
          "damaged file): retrain the model",
          where, m.input_names[k], m.scaler.min[k], m.scaler.max[k], lo, hi));
  }
  for (std::size_t c = 0; c < m.class_names.size(); ++c) {
    if (std::find(m.classes.begin(), m.classes.end(), static_cast<int>(c)) == m.classes.end())
      throw FormatError(fmt::format("{}: class '{}' has no training row", where, m.class_names[c]));
  }
  if (m.class_names.size() < 2)
    throw FormatError(fmt::format("{}: {} class(es); a classifier needs at least 2", where,
                                  m.class_names.size()));
}

}  // namespace

RecordingLabels read_recording_labels(const std::filesystem::path& path) {
  const std::string where = path.string();
  std::ifstream in(path);
  if (!in) throw FormatError(fmt::format("{}: cannot open labels file", where));
  csv::LineReader lines(in);
  std::string line;
  if (!lines.next(line)) throw FormatError(fmt::format("{}: empty labels file", where));
  const auto header = split(line);
  const auto column = [&](const char* name) {
    return static_cast<int>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  const int file_col = column("file"), class_col = column("class"), value_col = column("value");
  const int width = static_cast<int>(header.size());
  if (file_col == width || class_col == width)
    throw FormatError(
        fmt::format("{}: line 1: header needs columns 'file' and 'class' (has '{}')", where, line));
  for (const auto& h : header) {
    if (h != "file" && h != "class" && h != "value")
      throw FormatError(fmt::format("{}: line 1: unknown column '{}'", where, h));
    if (std::count(header.begin(), header.end(), h) > 1)
      throw FormatError(fmt::format("{}: line 1: column '{}' appears twice", where, h));
  }
  RecordingLabels labels;
  labels.has_values = value_col != width;
  std::set<std::string> seen;
  while (lines.next(line)) {
    const std::size_t number = lines.number();
    if (trim(line).empty()) continue;
    const auto f = split(line);
    if (static_cast<int>(f.size()) != width)
      throw FormatError(
          fmt::format("{}: line {}: {} fields, header has {}", where, number, f.size(), width));
    RecordingLabel l{f[file_col], f[class_col], 0.0};
    if (l.file.empty() || l.label.empty())
      throw FormatError(fmt::format("{}: line {}: empty file or class", where, number));
    // Recordings are read from (and `classify test --csv` names its outputs after) this path
    // inside the recordings folder: it may not lead out of it.
    const std::filesystem::path file_path(l.file);
    if (file_path.is_absolute() ||
        std::any_of(file_path.begin(), file_path.end(), [](const auto& p) { return p == ".."; }))
      throw FormatError(fmt::format(
          "{}: line {}: file '{}' must be a path inside the recordings folder (relative, no '..')",
          where, number, l.file));
    if (!seen.insert(l.file).second)
      throw FormatError(fmt::format("{}: line {}: {} is labelled twice", where, number, l.file));
    if (labels.has_values) {
      std::size_t used = 0;
      try {
        l.value = std::stod(f[value_col], &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != f[value_col].size())
        throw FormatError(
            fmt::format("{}: line {}: value '{}' is not a number", where, number, f[value_col]));
      // A curvature or a footprint in mm; far beyond any, a value is a typing error.
      l.value =
          checks::in_range(l.value, -1e6, 1e6, fmt::format("{}: line {}", where, number), "value");
    }
    labels.rows.push_back(std::move(l));
  }
  if (labels.rows.empty()) throw FormatError(fmt::format("{}: no labelled recordings", where));
  return labels;
}

LabelledRecordings read_labelled_recordings(const std::filesystem::path& dir,
                                            const std::filesystem::path& labels_path,
                                            const std::vector<std::string>& known_classes,
                                            int threads) {
  const auto labels = read_recording_labels(labels_path);
  LabelledRecordings d;
  d.class_names = known_classes;
  for (const auto& l : labels.rows) {
    const auto path = dir / l.file;
    if (!std::filesystem::is_regular_file(path))
      throw std::runtime_error(fmt::format("{}: labelled in {} but not in the recordings folder {}",
                                           path.string(), labels_path.string(), dir.string()));
    auto it = std::find(d.class_names.begin(), d.class_names.end(), l.label);
    if (it == d.class_names.end()) {
      if (!known_classes.empty())
        throw std::runtime_error(fmt::format("{}: unknown label '{}' (the model knows: {})",
                                             path.string(), l.label,
                                             fmt::join(known_classes, ", ")));
      d.class_names.push_back(l.label);
      it = d.class_names.end() - 1;
    }
    d.files.push_back(l.file);
    d.classes.push_back(static_cast<int>(it - d.class_names.begin()));
    if (labels.has_values) d.values.push_back(l.value);
  }
  d.recordings.resize(d.files.size());
  parallel_for(d.files.size(), worker_count(threads),
               [&](std::size_t i) { d.recordings[i] = read_sensor_csv(dir / d.files[i]); });
  return d;
}

LabelledInputs analyse_recordings(const LabelledRecordings& data,
                                  const RecordingInputOptions& options, int threads) {
  LabelledInputs d;
  d.options = options;
  d.input_names = recording_input_names(options);
  d.class_names = data.class_names;
  d.files = data.files;
  d.classes = data.classes;
  d.values = data.values;
  d.rows.resize(d.files.size());
  parallel_for(d.files.size(), worker_count(threads),
               [&](std::size_t i) { d.rows[i] = recording_inputs(data.recordings[i], options); });
  return d;
}

LabelledInputs load_labelled_recordings(const std::filesystem::path& dir,
                                        const std::filesystem::path& labels_path,
                                        const RecordingInputOptions& options,
                                        const std::vector<std::string>& known_classes,
                                        int threads) {
  // The input names first: a bad set of groups is reported before any file is read.
  recording_input_names(options);
  return analyse_recordings(read_labelled_recordings(dir, labels_path, known_classes, threads),
                            options, threads);
}

ClassifierModel make_classifier_model(const LabelledInputs& data, const SvmOptions& svm) {
  ClassifierModel m;
  m.options = data.options;
  m.input_names = data.input_names;
  m.class_names = data.class_names;
  m.svm = svm;
  m.scaler = MinMaxScaler::fit(data.rows);
  m.files = data.files;
  m.rows = data.rows;
  m.classes = data.classes;
  m.values = data.values;
  return m;
}

SvmOptions default_svm_options(RecordingProcedure procedure) {
  SvmOptions svm;
  if (procedure == RecordingProcedure::stroke) svm.c = 100.0;
  return svm;
}

RecordingInputOptions recording_inputs_for(const ClassifierTraining& t) {
  auto in = default_recording_inputs(t.procedure);
  if (t.baseline_at) in.contact.baseline_at = *t.baseline_at;
  if (t.electrodes) in.contact.electrodes = *t.electrodes;
  if (t.trim) {
    check_trim_fraction(*t.trim);
    in.contact.trim_fraction = *t.trim;
  }
  if (!t.inputs.empty()) in.groups = t.inputs;
  return in;
}

SvmOptions svm_options_for(const ClassifierTraining& t) {
  auto svm = default_svm_options(t.procedure);
  svm.degree = t.kernel_degree.value_or(svm.degree);
  svm.c = t.c.value_or(svm.c);
  return svm;
}

void require_two_classes(const std::vector<std::string>& class_names,
                         const std::filesystem::path& labels) {
  if (class_names.size() < 2) {
    throw std::runtime_error(
        fmt::format("classify train: {}: {} class(es) ({}); a classifier "
                    "needs recordings of at least 2 classes",
                    labels.string(), class_names.size(), fmt::join(class_names, ", ")));
  }
}

void write_classifier_model(const std::filesystem::path& path, const ClassifierModel& m) {
  nlohmann::json j;
  j["format"] = "tactile classifier model";
  j["version"] = m.version;
  j["procedure"] = to_string(recording_procedure(m.options));
  j["input_groups"] = names_of(m.options.groups);
  j["contact"] = {{"baseline_at", to_string(m.options.contact.baseline_at)},
                  {"baseline_s", m.options.contact.baseline_s},
                  {"threshold_fraction", m.options.contact.threshold_fraction},
                  {"min_threshold", m.options.contact.min_threshold},
                  {"trim_fraction", m.options.contact.trim_fraction},
                  {"electrodes", to_string(m.options.contact.electrodes)}};
  j["input_names"] = m.input_names;
  j["class_names"] = m.class_names;
  if (m.selection) {
    auto& candidates = j["selection"]["candidates"] = nlohmann::json::array();
    for (const auto& c : m.selection->candidates)
      candidates.push_back({{"input_groups", names_of(c.inputs.groups)},
                            {"baseline_at", to_string(c.inputs.contact.baseline_at)},
                            {"electrodes", to_string(c.inputs.contact.electrodes)},
                            {"trim_fraction", c.inputs.contact.trim_fraction},
                            {"degree", c.svm.degree},
                            {"c", c.svm.c},
                            {"correct", c.correct},
                            {"tested", c.tested}});
    j["selection"]["folds"] = m.selection->folds;
    j["selection"]["chosen"] = m.selection->chosen;
  }
  j["svm"] = {{"kernel", "polynomial"},
              {"degree", m.svm.degree},
              {"c", m.svm.c},
              {"tolerance", m.svm.tolerance},
              {"epsilon", m.svm.epsilon}};
  j["scaler"] = {{"min", m.scaler.min}, {"max", m.scaler.max}};
  j["has_values"] = !m.values.empty();
  auto& training = j["training"] = nlohmann::json::array();
  for (std::size_t i = 0; i < m.files.size(); ++i) {
    nlohmann::json row = {{"file", m.files[i]},
                          {"class", m.class_names.at(static_cast<std::size_t>(m.classes[i]))},
                          {"inputs", m.rows[i]}};
    if (!m.values.empty()) row["value"] = m.values[i];
    training.push_back(std::move(row));
  }
  write_text_atomically(path, j.dump(1) + "\n");
}

ClassifierModel read_classifier_model(const std::filesystem::path& path) {
  const std::string where = path.string();
  const nlohmann::json j = read_json_object(path, "model file");
  const auto& format = field(j, "format", where, &nlohmann::json::is_string, "a string");
  if (format != "tactile classifier model")
    throw FormatError(
        fmt::format("{}: not a classifier model (format '{}')", where, format.get<std::string>()));
  const auto& version =
      field(j, "version", where, &nlohmann::json::is_number_integer, "an integer");
  // Compared as read: narrowed to int first, 4294967297 would pass as version 1.
  const std::string version_text = version.dump();
  const auto known = [](auto v) {
    return v >= 1 && v <= static_cast<decltype(v)>(kClassifierModelVersion);
  };
  if (!(version.is_number_unsigned() ? known(version.get<std::uint64_t>())
                                     : known(version.get<std::int64_t>())))
    throw FormatError(fmt::format(
        "{}: model format version {}, this program reads versions 1 to {}: retrain the model",
        where, version_text, kClassifierModelVersion));
  // Version 1 had no trim_fraction or electrodes: its inputs are those of no trim and clusters.
  const bool v1 = version.get<std::int64_t>() == 1;
  ClassifierModel m;
  try {
    set_recording_procedure(m.options,
                            parse_recording_procedure(
                                field(j, "procedure", where, &nlohmann::json::is_string, "a string")
                                    .get<std::string>()));
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: {}", where, e.what()));
  }
  const auto groups_of = [&](const nlohmann::json& o) {
    std::vector<InputGroup> groups;
    for (const auto& name : array_of<std::string>(o, "input_groups", where)) {
      try {
        groups.push_back(parse_input_group(name));
      } catch (const std::invalid_argument& e) {
        throw FormatError(fmt::format("{}: {}", where, e.what()));
      }
    }
    return groups;
  };
  m.options.groups = groups_of(j);  // the file's groups, not the defaults
  const auto& contact = field(j, "contact", where, &nlohmann::json::is_object, "an object");
  const auto word = [&](const nlohmann::json& o, const char* key) {
    return field(o, key, where, &nlohmann::json::is_string, "a string").get<std::string>();
  };
  const auto number = [&](const nlohmann::json& o, const char* key) {
    return field(o, key, where, &nlohmann::json::is_number, "a number").get<double>();
  };
  const auto integer = [&](const nlohmann::json& o, const char* key) {
    return field(o, key, where, &nlohmann::json::is_number_integer, "an integer").get<int>();
  };
  try {
    m.options.contact.baseline_at = parse_baseline_at(word(contact, "baseline_at"));
    if (!v1) {
      m.options.contact.electrodes = parse_electrodes(word(contact, "electrodes"));
      m.options.contact.trim_fraction = number(contact, "trim_fraction");
      check_trim_fraction(m.options.contact.trim_fraction);
    }
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: contact: {}", where, e.what()));
  }
  // Ranges a trained model can have (`classify train` takes C from 0.001 to 100000): anything
  // else is a damaged or hand-edited file, refused here rather than mis-classifying later.
  const auto in_range = [&](const nlohmann::json& o, const char* key, double min, double max) {
    return checks::in_range(number(o, key), min, max, where, key);
  };
  m.options.contact.baseline_s = in_range(contact, "baseline_s", 0, 3600);
  m.options.contact.threshold_fraction = in_range(contact, "threshold_fraction", 0, 1);
  m.options.contact.min_threshold = in_range(contact, "min_threshold", 0, 1e9);
  m.input_names = array_of<std::string>(j, "input_names", where);
  std::vector<std::string> expected;
  try {
    expected = recording_input_names(m.options);
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: {}", where, e.what()));
  }
  if (m.input_names != expected)
    throw FormatError(fmt::format(
        "{}: mismatched inputs: the model has {} inputs ({}), this program computes {} for {} "
        "with groups {} ({}): retrain the model",
        where, m.input_names.size(), fmt::join(m.input_names, ","), expected.size(),
        to_string(recording_procedure(m.options)), fmt::join(names_of(m.options.groups), ","),
        fmt::join(expected, ",")));
  m.class_names = array_of<std::string>(j, "class_names", where);
  const auto& svm = field(j, "svm", where, &nlohmann::json::is_object, "an object");
  m.svm.degree =
      field(svm, "degree", where, &nlohmann::json::is_number_integer, "an integer").get<int>();
  checks::int_in_range(m.svm.degree, 1, 2, where, "degree");
  m.svm.c = in_range(svm, "c", 0.001, 100000);
  m.svm.tolerance = in_range(svm, "tolerance", 1e-12, 1);
  m.svm.epsilon = in_range(svm, "epsilon", 0, 1e6);
  const auto& scaler = field(j, "scaler", where, &nlohmann::json::is_object, "an object");
  m.scaler.min = array_of<double>(scaler, "min", where);
  m.scaler.max = array_of<double>(scaler, "max", where);
  const bool has_values =
      field(j, "has_values", where, &nlohmann::json::is_boolean, "true or false").get<bool>();
  const auto& training = field(j, "training", where, &nlohmann::json::is_array, "an array");
  for (const auto& row : training) {
    if (!row.is_object())
      throw FormatError(fmt::format("{}: training rows must be objects", where));
    m.files.push_back(
        field(row, "file", where, &nlohmann::json::is_string, "a string").get<std::string>());
    const auto label =
        field(row, "class", where, &nlohmann::json::is_string, "a string").get<std::string>();
    const auto it = std::find(m.class_names.begin(), m.class_names.end(), label);
    if (it == m.class_names.end())
      throw FormatError(fmt::format("{}: training row {} has class '{}', not in class_names", where,
                                    m.files.back(), label));
    m.classes.push_back(static_cast<int>(it - m.class_names.begin()));
    m.rows.push_back(array_of<double>(row, "inputs", where));
    if (m.rows.back().size() != m.input_names.size())
      throw FormatError(fmt::format("{}: training row {} has {} inputs, the model {}", where,
                                    m.files.back(), m.rows.back().size(), m.input_names.size()));
    if (has_values) m.values.push_back(number(row, "value"));
  }
  if (m.rows.empty()) throw FormatError(fmt::format("{}: no training rows", where));
  if (const auto it = j.find("selection"); it != j.end()) {
    const auto& sel = field(j, "selection", where, &nlohmann::json::is_object, "an object");
    SelectionRecord record;
    record.folds = integer(sel, "folds");
    const auto& candidates = field(sel, "candidates", where, &nlohmann::json::is_array, "an array");
    for (const auto& c : candidates) {
      if (!c.is_object())
        throw FormatError(fmt::format("{}: selection candidates must be objects", where));
      SelectionCandidate candidate;
      candidate.inputs = m.options;
      candidate.inputs.groups = groups_of(c);
      try {
        candidate.inputs.contact.baseline_at = parse_baseline_at(word(c, "baseline_at"));
        candidate.inputs.contact.electrodes = parse_electrodes(word(c, "electrodes"));
      } catch (const std::invalid_argument& e) {
        throw FormatError(fmt::format("{}: selection: {}", where, e.what()));
      }
      candidate.inputs.contact.trim_fraction = number(c, "trim_fraction");
      candidate.svm = m.svm;
      candidate.svm.degree = integer(c, "degree");
      candidate.svm.c = number(c, "c");
      candidate.correct = integer(c, "correct");
      candidate.tested = integer(c, "tested");
      record.candidates.push_back(std::move(candidate));
    }
    const int chosen = integer(sel, "chosen");
    if (chosen < 0 || static_cast<std::size_t>(chosen) >= record.candidates.size())
      throw FormatError(fmt::format("{}: selection: chosen {} is not one of the {} candidates",
                                    where, chosen, record.candidates.size()));
    record.chosen = static_cast<std::size_t>(chosen);
    m.selection = std::move(record);
  }
  if (m.scaler.min.size() != m.input_names.size() || m.scaler.max.size() != m.input_names.size())
    throw FormatError(
        fmt::format("{}: scaler does not match the {} inputs", where, m.input_names.size()));
  check_training_rows(m, where);
  return m;
}

Classifier::Classifier(const ClassifierModel& m)
    : svc_(SvmModel::train_classifier(m.rows, m.classes, m.svm)),
      svr_(m.class_names.size()),
      class_value_(m.class_names.size(), 0.0),
      has_values_(!m.values.empty()) {
  if (!has_values_) return;
  for (std::size_t c = 0; c < m.class_names.size(); ++c) {
    SvmRows x;
    std::vector<double> y;
    for (std::size_t i = 0; i < m.rows.size(); ++i)
      if (static_cast<std::size_t>(m.classes[i]) == c) {
        x.push_back(m.rows[i]);
        y.push_back(m.values[i]);
      }
    if (y.empty()) continue;
    // A class whose rows all share one value needs no regression (and SVR of a constant
    // target is degenerate): it predicts that value.
    if (std::all_of(y.begin(), y.end(), [&](double v) { return v == y.front(); }))
      class_value_[c] = y.front();
    else
      svr_[c].push_back(SvmModel::train_regressor(x, y, m.svm));
  }
}

ClassPrediction Classifier::predict(const std::vector<double>& inputs) const {
  ClassPrediction p;
  p.class_index = static_cast<int>(std::lround(svc_.predict(inputs)));
  if (has_values_) {
    const auto c = static_cast<std::size_t>(p.class_index);
    p.value = svr_[c].empty() ? class_value_[c] : svr_[c].front().predict(inputs);
  }
  return p;
}

ClassifierTest test_classifier(const Classifier& classifier, std::size_t class_count,
                               const LabelledInputs& test) {
  ClassifierTest t;
  t.confusion.assign(class_count, std::vector<int>(class_count, 0));
  for (std::size_t i = 0; i < test.rows.size(); ++i) {
    const auto p = classifier.predict(test.rows[i]);
    t.predictions.push_back(p);
    ++t.confusion.at(static_cast<std::size_t>(test.classes[i]))
          .at(static_cast<std::size_t>(p.class_index));
    t.correct += p.class_index == test.classes[i] ? 1 : 0;
    ++t.tested;
  }
  return t;
}

LabelledInputs subset(const LabelledInputs& data, const std::vector<std::size_t>& keep) {
  LabelledInputs s;
  s.options = data.options;
  s.input_names = data.input_names;
  s.class_names = data.class_names;
  for (const std::size_t i : keep) {
    s.files.push_back(data.files.at(i));
    s.rows.push_back(data.rows.at(i));
    s.classes.push_back(data.classes.at(i));
    if (!data.values.empty()) s.values.push_back(data.values.at(i));
  }
  return s;
}

std::vector<int> stratified_folds(const std::vector<int>& classes, int folds) {
  std::vector<int> fold_of(classes.size());
  std::map<int, int> seen_in_class;
  for (std::size_t i = 0; i < classes.size(); ++i) fold_of[i] = seen_in_class[classes[i]]++ % folds;
  return fold_of;
}

std::pair<int, int> class_sizes(const std::vector<int>& classes) {
  std::map<int, int> count;
  for (const int c : classes) ++count[c];
  std::pair<int, int> range{0, 0};
  for (const auto& [c, n] : count) {
    range.first = range.first == 0 ? n : std::min(range.first, n);
    range.second = std::max(range.second, n);
  }
  return range;
}

void check_fold_count(const std::vector<int>& classes, int folds) {
  const int largest = class_sizes(classes).second;
  if (folds < 2 || folds > largest)
    throw std::invalid_argument(
        fmt::format("cross-validation with {} folds: needs 2 to {} folds (the largest class has {} "
                    "recordings; more folds would be empty)",
                    folds, std::max(2, largest), largest));
}

CrossValidation pool_folds(const std::vector<ClassifierTest>& folds) {
  CrossValidation cv;
  const double k = static_cast<double>(folds.size());
  for (const auto& r : folds) {
    cv.fold_accuracy.push_back(r.accuracy());
    cv.correct += r.correct;
    cv.tested += r.tested;
    cv.mean += r.accuracy() / k;
  }
  double ss = 0;
  for (double a : cv.fold_accuracy) ss += (a - cv.mean) * (a - cv.mean);
  cv.spread = folds.size() > 1 ? std::sqrt(ss / (k - 1)) : 0.0;
  return cv;
}

CrossValidation cross_validate(const LabelledInputs& data, const SvmOptions& svm, int folds,
                               int threads) {
  check_fold_count(data.classes, folds);
  const auto fold_of = stratified_folds(data.classes, folds);
  std::vector<ClassifierTest> results(static_cast<std::size_t>(folds));
  parallel_for(results.size(), worker_count(threads), [&](std::size_t k) {
    std::vector<std::size_t> train, test;
    for (std::size_t i = 0; i < data.rows.size(); ++i)
      (fold_of[i] == static_cast<int>(k) ? test : train).push_back(i);
    const Classifier c(make_classifier_model(subset(data, train), svm));
    results[k] = test_classifier(c, data.class_names.size(), subset(data, test));
  });
  return pool_folds(results);
}

}  // namespace tactile::perception
