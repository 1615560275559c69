// A live session; see live_session.hpp.

#include "tactile/live/live_session.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <future>
#include <limits>
#include <mutex>
#include <optional>
#include <thread>
#if defined(__linux__)
#include <sched.h>
#endif
#include <utility>

#include "live_source.hpp"
#include "tactile/capture/capture.hpp"
#include "tactile/capture/causal_smoothing.hpp"
#include "tactile/capture/contact_map.hpp"
#include "tactile/capture/contact_strain.hpp"
#include "tactile/capture/features.hpp"
#include "tactile/capture/neighbour_smoothing.hpp"
#include "tactile/capture/track.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/stats.hpp"
#include "tactile/display/frame_codec.hpp"
#include "tactile/display/player.hpp"
#include "tactile/live/frame_queue.hpp"
#include "tactile/mapping/methods.hpp"
#include "tactile/mapping/placement.hpp"
#include "tactile/mapping/strain_field.hpp"

namespace tactile::live {

namespace {

double ms_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// The newest mapped frame, held for the device feeder, and when each camera frame was first
// sent.
class HeldFrame {
 public:
  explicit HeldFrame(std::size_t contactors) : deflection_um_(contactors, 0.0f) {}
  void publish(std::int64_t frame, std::vector<float> deflection_um) {
    std::lock_guard lock(mutex_);
    deflection_um_ = std::move(deflection_um);
    frame_ = frame;
    published_ = true;
  }
  // The frame to send now; `frame` is -1 before any.
  std::int64_t take(std::vector<float>& out) {
    std::lock_guard lock(mutex_);
    out = deflection_um_;
    return published_ ? frame_ : -1;
  }
  void sent(std::int64_t frame, Clock::time_point at) {
    {
      std::lock_guard lock(mutex_);
      if (frame > last_sent_frame_) {
        last_sent_frame_ = frame;
        last_sent_at_ = at;
      }
    }
    changed_.notify_all();
  }
  // When `frame` (or a later one) first left the host; waits for it (or until `give_up`).
  std::optional<Clock::time_point> wait_sent(std::int64_t frame, Clock::time_point give_up) {
    std::unique_lock lock(mutex_);
    if (!changed_.wait_until(lock, give_up, [&] { return last_sent_frame_ >= frame; })) {
      return std::nullopt;
    }
    return last_sent_at_;
  }

 private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<float> deflection_um_;
  std::int64_t frame_ = -1;
  bool published_ = false;
  std::int64_t last_sent_frame_ = -1;
  Clock::time_point last_sent_at_{};
};

// The calling thread into the scheduler's idle class or back to the normal one; false where
// refused. For the session's side work (detection, the smoothing's choice) while the session is
// short of time for the camera: there it would take a core from the tracker's two workers for
// the frames it runs on. A session with time to spare keeps it at normal priority, where other
// load cannot starve it (a full-slip session needs a detection every frame).
bool to_idle_class(bool idle) {
#if defined(__linux__)
  sched_param none{};
  none.sched_priority = 0;
  return sched_setscheduler(0, idle ? SCHED_IDLE : SCHED_OTHER, &none) == 0;
#else
  (void)idle;
  return false;
#endif
}

// Detection of new landmarks off the processing thread. The ridge-blob detector takes tens of
// milliseconds on a 320 x 240 frame, several camera frames at 120 Hz: in line it would delay
// those frames and drop the next ones. Its landmarks arrive a few frames later, found on the
// tracker's frame given with the job, and the tracker carries them to the current frame by
// the motion of the tracks around each.
class AsyncDetector {
 public:
  AsyncDetector(double px_per_mm, const capture::FeatureParams& params)
      : px_per_mm_(px_per_mm), params_(params), thread_([this] { loop(); }) {}
  ~AsyncDetector() {
    {
      std::lock_guard lock(mutex_);
      quit_ = true;
    }
    changed_.notify_all();
    thread_.join();
  }
  AsyncDetector(const AsyncDetector&) = delete;
  AsyncDetector& operator=(const AsyncDetector&) = delete;

  bool busy() {
    std::lock_guard lock(mutex_);
    return job_.has_value() || working_;
  }
  void submit(std::int64_t frame, const capture::GrayImage& image) {
    {
      std::lock_guard lock(mutex_);
      job_.emplace(frame, image);
    }
    changed_.notify_all();
  }
  // Whether detections run in the scheduler's idle class (from the next one on; to_idle_class).
  void set_idle(bool idle) {
    std::lock_guard lock(mutex_);
    idle_ = idle;
  }
  // A finished detection (its frame and landmarks), once; rethrows the detector's failure.
  std::optional<std::pair<std::int64_t, std::vector<capture::Feature>>> take() {
    std::lock_guard lock(mutex_);
    if (failure_) std::rethrow_exception(std::exchange(failure_, nullptr));
    return std::exchange(result_, std::nullopt);
  }

 private:
  void loop() {
    bool in_idle_class = false;
    std::unique_lock lock(mutex_);
    while (true) {
      changed_.wait(lock, [this] { return quit_ || job_.has_value(); });
      if (quit_) return;
      auto [frame, image] = std::move(*job_);
      job_.reset();
      working_ = true;
      const bool idle = idle_;
      lock.unlock();
      if (idle != in_idle_class) in_idle_class = to_idle_class(idle) ? idle : in_idle_class;
      std::vector<capture::Feature> found;
      std::exception_ptr failure;
      try {
        found = capture::extract_features(image, px_per_mm_, params_);
      } catch (...) {
        failure = std::current_exception();
      }
      lock.lock();
      working_ = false;
      if (failure) {
        failure_ = failure;
      } else {
        result_.emplace(frame, std::move(found));
      }
    }
  }

  double px_per_mm_;
  capture::FeatureParams params_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<std::pair<std::int64_t, capture::GrayImage>> job_;
  std::optional<std::pair<std::int64_t, std::vector<capture::Feature>>> result_;
  std::exception_ptr failure_;
  bool working_ = false;
  bool quit_ = false;
  bool idle_ = false;
  std::thread thread_;  // last: started once the members it uses exist
};

// The causal smoothing's window chosen off the processing thread: the choice reads every track's
// last second of positions (milliseconds on a large frame), which in line would delay the frame
// it falls on. A choice due while the last one still runs is skipped.
class AsyncWindowChoice {
 public:
  // In the scheduler's idle class where `idle` (to_idle_class).
  void start(std::vector<capture::Track> tracks, int degree, double max_residual_px,
             double noise_scale, bool idle) {
    if (pending_.valid()) return;
    pending_ = std::async(std::launch::async, [tracks = std::move(tracks), degree, max_residual_px,
                                               noise_scale, idle] {
      if (idle) to_idle_class(true);
      return capture::causal_smoothing_that_fits(tracks, degree, max_residual_px, 1, noise_scale);
    });
  }
  // A finished choice, once; rethrows the choice's failure.
  std::optional<int> take() {
    if (!pending_.valid() ||
        pending_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
      return std::nullopt;
    }
    return pending_.get();
  }

 private:
  std::future<int> pending_;
};

// Sends the held frame at the device's rate, keeping its FIFO `target` frames deep.
void feed_device(display::Transport& device, std::uint32_t fifo_capacity_frames, double rate_hz,
                 int target, HeldFrame& held, const std::atomic<bool>& done,
                 std::int64_t& frames_sent, std::exception_ptr& failure) {
  try {
    const auto period =
        std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(1.0 / rate_hz));
    std::vector<float> frame;
    std::uint32_t sequence = 0;
    // A device without a FIFO (a Latero: a frame plays when it arrives) takes one a tick.
    const int depth =
        std::min<int>(target, static_cast<int>(std::max<std::uint32_t>(1, fifo_capacity_frames)));
    auto tick = Clock::now();
    while (!done.load()) {
      const display::DeviceStatus status = device.status();
      int room = depth - static_cast<int>(status.fifo_fill);
      while (room-- > 0) {
        const std::int64_t camera_frame = held.take(frame);
        const auto bytes = display::encode_frame(frame, sequence, false);
        if (!device.send_frame(bytes)) break;
        ++sequence;
        ++frames_sent;
        held.sent(camera_frame, Clock::now());
      }
      tick += period;
      std::this_thread::sleep_until(tick);
    }
  } catch (...) {
    failure = std::current_exception();
  }
}

// One camera frame handed from the tracking to the strain and mapping.
struct TrackedFrame {
  SourceFrame frame;
  FrameTiming timing;                    // its times so far
  std::optional<std::int64_t> previous;  // the camera frame its steps start from
  std::vector<capture::Track> steps;     // last_step(), smoothed
  bool view_slid = false;                // the view has slid on this frame or before
  Clock::time_point tracked_at;
};

}  // namespace

capture::Calibration session_calibration(const ResolvedLive& session, int width_px, int height_px) {
  if (session.calibration) {
    capture::check_calibration_fits(*session.calibration, width_px, height_px, "--calib",
                                    session.source);
    return *session.calibration;
  }
  return capture::uniform_calibration(session.px_per_mm.value(), width_px, height_px);
}

LiveSummary run_live(const ResolvedLive& session, display::Transport& device,
                     const std::atomic<bool>& stop, const LiveCallbacks& callbacks,
                     const LiveOptions& options) {
  const Clock::time_point start = Clock::now();
  std::unique_ptr<FrameSource> source = session.rehearsal
                                            ? open_rehearsal(session.source, session.rate_hz, start)
                                            : open_device(session.source, session.rate_hz);
  return run_live_from(*source, start, session, device, stop, callbacks, options);
}

SessionThread::SessionThread(const ResolvedLive& session, display::Transport& device,
                             std::atomic<bool>& stop, LiveCallbacks callbacks,
                             std::function<void()> on_end)
    : stop_(stop),
      thread_(
          [this, &session, &device, callbacks = std::move(callbacks), on_end = std::move(on_end)] {
            try {
              summary_ = run_live(session, device, stop_, callbacks);
            } catch (...) {
              failure_ = std::current_exception();
            }
            if (on_end) on_end();
            done_ = true;
          }) {}

SessionThread::~SessionThread() {
  if (!thread_.joinable()) return;
  stop_ = true;
  thread_.join();
}

void SessionThread::wait() {
  if (thread_.joinable()) thread_.join();
}

LiveSummary SessionThread::result() {
  wait();
  if (failure_) std::rethrow_exception(failure_);
  return summary_;
}

LiveSummary run_live_from(FrameSource& source_frames, Clock::time_point start,
                          const ResolvedLive& session, display::Transport& device,
                          const std::atomic<bool>& stop, const LiveCallbacks& callbacks,
                          const LiveOptions& options) {
  FrameSource* source = &source_frames;
  callbacks.note(source->describe());
  LiveSummary summary;
  summary.source = session.source;
  summary.camera_rate_hz = source->rate_hz();
  const double device_rate_hz = session.params.rate_hz.value();
  summary.device_rate_hz = device_rate_hz;
  const std::optional<Clock::time_point> end_at =
      session.seconds ? std::optional(start + std::chrono::duration_cast<Clock::duration>(
                                                  std::chrono::duration<double>(*session.seconds)))
                      : std::nullopt;

  // Before any thread: a device that cannot take the layout or start fails here, with nothing
  // to join.
  // Asked once: a Latero answers info() with a probe over the network.
  const display::DeviceInfo device_info = device.info();
  display::check_layout_against_device(session.layout, device_rate_hz, device_info);
  device.start(device_rate_hz);

  // Acquisition: never waits for processing.
  const int queue_frames = session.queue_frames.value_or(queue_frames_for(summary.camera_rate_hz));
  DropOldestQueue<SourceFrame> queue(static_cast<std::size_t>(queue_frames));
  callbacks.note(fmt::format(
      "queue of {} frame{}{}; when full the oldest is dropped", queue_frames,
      queue_frames == 1 ? "" : "s",
      summary.camera_rate_hz > 0
          ? fmt::format(" ({:.0f} ms at {:g} Hz{})", 1000.0 * queue_frames / summary.camera_rate_hz,
                        summary.camera_rate_hz,
                        session.queue_frames ? "" : ": room for the first frame's extra work")
          : std::string()));
  std::atomic<bool> acquisition_done{false};
  std::atomic<bool> halt{false};  // the processing ended (a stop, the end or a failure)
  std::exception_ptr acquisition_failure;
  std::vector<SourceFrame> dropped;
  std::mutex dropped_mutex;
  std::int64_t frames_in = 0;
  std::int64_t frames_driver_stamped = 0;
  std::thread acquisition([&] {
    try {
      SourceFrame frame;
      while (!stop.load() && !halt.load() && source->next(frame)) {
        if (end_at && frame.available > *end_at) break;
        ++frames_in;
        if (frame.driver_stamped) ++frames_driver_stamped;
        callbacks.received(frame.index,
                           std::chrono::duration<double>(frame.available - start).count(),
                           frame.image);
        if (auto old = queue.push(std::move(frame))) {
          std::lock_guard lock(dropped_mutex);
          old->image = {};
          dropped.push_back(std::move(*old));
        }
        frame = {};
      }
    } catch (...) {
      acquisition_failure = std::current_exception();
    }
    queue.close();
    acquisition_done = true;
  });

  const movie::Layout& layout = session.layout;
  HeldFrame held(static_cast<std::size_t>(layout.rows) * static_cast<std::size_t>(layout.cols));
  std::atomic<bool> feeding_done{false};
  std::int64_t frames_sent = 0;
  std::exception_ptr feed_failure;
  std::thread feeder([&] {
    feed_device(device, device_info.fifo_capacity_frames, device_rate_hz,
                options.fifo_target_frames, held, feeding_done, frames_sent, feed_failure);
  });

  std::unique_ptr<capture::AlignmentTracker> tracker;
  capture::CaptureChoice choice;  // on the first frame
  std::unique_ptr<AsyncDetector> detector;
  capture::RefineParams refine;
  capture::CausalTrackSmoother smoother(session.smoothing);
  std::optional<capture::NeighbourStepSmoother> neighbours;
  // The strain and mapping thread's last frame's time, for the tracks' density.
  std::atomic<double> strain_map_ms{0.0};
  AsyncWindowChoice window_choice;
  capture::FeatureParams features = capture::pores_only();
  capture::Calibration calibration;
  double px_per_mm = 0;
  mapping::Placement placement;
  std::vector<capture::PointMm> sample_points;
  // Where the skin touches, frame by frame (contact_map.hpp): once the view has slid, strain at
  // or beside skin out of contact is left out, as the batch capture does where skin slides
  // through the view; the tracker measures each step from one frame to the next with nothing
  // smoothed across frames, so the step's two frames count, and the frame before them: where skin
  // was out of contact a frame ago it may be landing still, at its last frame a spot smaller than
  // a cell (the batch capture sees such a spot from the frames on either side).
  capture::ContactGrid contact_cells;
  capture::RunningContact contact;
  std::vector<std::uint8_t> near_gap_before;  // in the step's first frame or the frame before it
  std::vector<std::uint8_t> near_gap_last;    // in the last frame alone
  bool view_slid = false;
  std::vector<FrameTiming> timings;
  const auto report_dropped = [&] {
    std::vector<SourceFrame> now;
    {
      std::lock_guard lock(dropped_mutex);
      now.swap(dropped);
    }
    for (const auto& d : now) {
      FrameTiming t;
      t.frame = d.index;
      t.source_time_s = std::chrono::duration<double>(d.available - start).count();
      t.dropped = true;
      t.latency_ms = std::numeric_limits<double>::quiet_NaN();
      callbacks.frame_done(t);
      timings.push_back(t);
    }
  };
  // Strain and mapping on a thread of their own, a frame behind the tracking: the tracker's
  // serial parts leave a core free, and a frame's strain and mapping then cost the next frame's
  // tracking nothing (640 x 484 at 60 Hz: tracking ~12 ms, strain and mapping ~3 ms of a
  // 16.7 ms period). The tracking runs at most kTrackedAhead frames ahead.
  constexpr std::size_t kTrackedAhead = 1;
  WaitingQueue<TrackedFrame> tracked_frames(kTrackedAhead);
  std::exception_ptr strain_failure;
  std::thread strain_and_mapping([&] {
    try {
      bool began = false;
      while (true) {
        std::optional<TrackedFrame> got = tracked_frames.pop(std::chrono::milliseconds(20));
        // Dropped frames are told from the first frame handed over on, after `started`.
        began = began || got.has_value();
        if (began) report_dropped();
        if (!got) {
          if (tracked_frames.closed_and_empty()) break;
          continue;
        }
        TrackedFrame& tf = *got;
        SourceFrame& f = tf.frame;
        FrameTiming& t = tf.timing;
        const Clock::time_point taken = Clock::now();
        t.wait_ms += ms_between(tf.tracked_at, taken);
        std::vector<capture::Track>& steps = tf.steps;
        const std::optional<std::int64_t>& previous = tf.previous;
        // Across the skin here rather than beside the tracking: at 640 x 484 a frame's fits take
        // a millisecond or more, which this thread has to spare while the next frame is tracked.
        if (previous) neighbours->smooth(steps);
        FrameContact frame_contact;
        frame_contact.frame = f.index;
        frame_contact.ridge_contrast =
            capture::cell_ridge_contrast(f.image, contact_cells, px_per_mm);
        frame_contact.in_contact = capture::contact_of_frame(contact, frame_contact.ridge_contrast);
        frame_contact.threshold_grey = capture::running_threshold_grey(contact);
        std::vector<std::uint8_t> near_gap =
            capture::cells_near_gap(contact_cells, frame_contact.in_contact);
        callbacks.contact(frame_contact);
        capture::StrainFrame sf;
        std::vector<float> deflection(
            static_cast<std::size_t>(layout.rows) * static_cast<std::size_t>(layout.cols), 0.0f);
        if (previous) {
          sf.frame_from = static_cast<std::int32_t>(*previous);
          sf.frame_to = static_cast<std::int32_t>(f.index);
          sf.t_s = t.source_time_s;
          capture::TracksById by_id;
          for (const auto& s : steps) {
            by_id.emplace(s.id, &s);
            const capture::PointMm a = capture::to_mm(calibration, s.x_px[0], s.y_px[0]);
            const capture::PointMm b = capture::to_mm(calibration, s.x_px[1], s.y_px[1]);
            sf.points_from.push_back({s.id, sf.frame_from, capture::FeatureType::pore, s.x_px[0],
                                      s.y_px[0], a.x_mm, a.y_mm});
            sf.points_to.push_back({s.id, sf.frame_to, capture::FeatureType::pore, s.x_px[1],
                                    s.y_px[1], b.x_mm, b.y_mm});
          }
          if (sf.points_from.size() >= 3) {
            capture::triangulate_strain(sf.points_from, sf.points_to, 3.0, sf.edges, sf.triangles);
            // The blend reads each step's two frames by the tracker's count, which skips the
            // camera frames the session dropped.
            const std::int32_t camera_from = sf.frame_from;
            sf.frame_from = steps.front().first_frame;
            sf.frame_to = sf.frame_from + 1;
            capture::blend_window_gradients(sf, by_id, calibration, capture::kWindowGradientShare);
            sf.frame_from = camera_from;
            sf.frame_to = static_cast<std::int32_t>(f.index);
            summary.strain_edges += static_cast<std::int64_t>(sf.edges.size());
            if (tf.view_slid) {
              summary.strain_edges_near_gaps +=
                  capture::leave_out_strain_near_gaps(sf, contact_cells, near_gap_before, near_gap);
            }
          }
          t.points = static_cast<int>(sf.points_to.size());
          t.edges = static_cast<int>(sf.edges.size());
          const Clock::time_point strained = Clock::now();
          t.strain_ms = ms_between(taken, strained);
          callbacks.strain(sf);
          if (!sf.triangles.empty()) {
            const mapping::StrainField field =
                mapping::build_strain_field(sf, session.params.field, sample_points);
            const std::vector<double> d =
                session.params.method == mapping::MappingMethod::proportional
                    ? mapping::proportional_frame(field, layout, placement,
                                                  session.params.gain_um_per_strain)
                    : mapping::integrated_frame(field, layout, placement,
                                                session.params.gain_um_per_strain);
            for (std::size_t i = 0; i < d.size() && i < deflection.size(); ++i) {
              deflection[i] = static_cast<float>(
                  std::clamp(d[i], layout.deflection_min_um, layout.deflection_max_um));
            }
          }
          t.map_ms = ms_between(strained, Clock::now());
          strain_map_ms = t.strain_ms + t.map_ms;
        }
        near_gap_before = near_gap;
        for (std::size_t i = 0; i < near_gap_last.size() && i < near_gap_before.size(); ++i) {
          near_gap_before[i] |= near_gap_last[i];
        }
        near_gap_last = std::move(near_gap);
        const Clock::time_point mapped = Clock::now();
        callbacks.mapped(f.index, deflection);
        held.publish(f.index, std::move(deflection));
        // Its first device frame: within a few device periods unless the device stalls.
        const auto sent = held.wait_sent(f.index, mapped + std::chrono::seconds(2));
        if (!sent) {
          throw std::runtime_error(fmt::format("the display took no frame for 2 s (frame {} of {})",
                                               f.index, session.source));
        }
        t.send_ms = ms_between(mapped, *sent);
        t.latency_ms = ms_between(f.available, *sent);
        ++summary.frames_processed;
        callbacks.frame_done(t);
        timings.push_back(t);
      }
    } catch (...) {
      strain_failure = std::current_exception();
    }
    // The tracking's next hand-over fails: the session ends.
    tracked_frames.close();
  });
  std::exception_ptr failure;
  try {
    std::optional<std::int64_t> previous;
    std::int64_t last_detection = 0;
    // The tracks' density: fixed, or kept to what the camera's period allows.
    double spacing_mm = session.min_spacing_mm.value_or(0.0);
    std::vector<double> recent_track_ms;
    bool judged_once = false;
    int tracks_after_detection = 0;
    while (!stop.load()) {
      std::optional<SourceFrame> got = queue.pop(std::chrono::milliseconds(20));
      if (!got) {
        // --seconds ends the session even while the source sends nothing.
        if (queue.closed_and_empty() || (end_at && Clock::now() > *end_at)) break;
        continue;
      }
      SourceFrame& f = *got;
      FrameTiming t;
      t.frame = f.index;
      t.source_time_s = std::chrono::duration<double>(f.available - start).count();
      const Clock::time_point popped = Clock::now();
      t.wait_ms = ms_between(f.available, popped);
      if (!tracker) {
        summary.width_px = f.image.width_px;
        summary.height_px = f.image.height_px;
        calibration = session_calibration(session, f.image.width_px, f.image.height_px);
        px_per_mm = 1.0 / calibration.mm_per_px;
        // The detector the batch capture would choose on this frame (its landmarks there are
        // the first seeds: the choice has found them).
        if (session.pores == capture::PoreSetting::automatic) {
          choice = capture::choose_capture_settings(f.image, px_per_mm, features);
        } else {
          choice.detector = session.pores == capture::PoreSetting::ridge_blob
                                ? capture::PoreDetector::ridge_blob
                                : capture::PoreDetector::paper;
        }
        features.pore_detector = choice.detector;
        summary.detector = capture::to_string(choice.detector);
        refine.window_mm = session.refine_window_mm;
        tracker = std::make_unique<capture::AlignmentTracker>(px_per_mm, refine, options.threads);
        neighbours.emplace(session.neighbour_smoothing, px_per_mm);
        tracker->set_min_spacing_px(spacing_mm * px_per_mm);
        summary.min_spacing_mm = spacing_mm;
        capture::StrainMovie frame_of_view;
        frame_of_view.calibration = calibration;
        frame_of_view.field_width_mm = f.image.width_px * calibration.mm_per_px;
        frame_of_view.field_height_mm = f.image.height_px * calibration.mm_per_px;
        placement = session.params.placement.value_or(mapping::default_placement(frame_of_view));
        sample_points = mapping::sample_points_mm(layout, placement);
        contact_cells = capture::contact_grid(f.image.width_px, f.image.height_px, px_per_mm);
        callbacks.note(fmt::format("{} x {} px at {:.2f} px/mm, pores: {}; {} at {:g} Hz",
                                   f.image.width_px, f.image.height_px, px_per_mm, summary.detector,
                                   layout.name, device_rate_hz));
        callbacks.started({session.source, calibration, summary.camera_rate_hz, layout,
                           device_rate_hz, contact_cells});
      }
      // Landmarks: detected every detect_every frames, or sooner when a fifth of the tracks
      // have ended since the last detection or the view slides (as the batch capture), followed by
      // alignment in between; detected in line on the first frame only, then on the detector's
      // thread.
      std::vector<capture::Feature> seeds;
      int seeds_frame = tracker->frames();
      bool seeded = false;
      if (tracker->frames() == 0) {
        seeds = session.pores == capture::PoreSetting::automatic
                    ? std::move(choice.first_frame_features)
                    : capture::extract_features(f.image, px_per_mm, features);
        detector = std::make_unique<AsyncDetector>(px_per_mm, features);
        seeded = true;
      } else {
        // Where the view slides new skin enters every frame: detected as often as the
        // detector's thread can.
        const bool due = f.index - last_detection >= session.detect_every ||
                         tracker->live_tracks() < 0.8 * tracks_after_detection ||
                         tracker->sliding();
        if (due && !detector->busy()) {
          detector->submit(tracker->frames(), f.image);
          last_detection = f.index;
        }
        if (auto found = detector->take()) {
          seeds_frame = static_cast<int>(found->first);
          seeds = std::move(found->second);
          seeded = true;
        }
      }
      tracker->add_frame(f.image, seeds, seeds_frame);
      if (seeded) tracks_after_detection = tracker->live_tracks();
      std::vector<capture::Track> steps = tracker->last_step();
      if (previous) {
        if (auto window = window_choice.take()) {
          smoother.set_window(*window);
          summary.smoothing_min_frames = summary.smoothing_choices == 0
                                             ? *window
                                             : std::min(summary.smoothing_min_frames, *window);
          summary.smoothing_max_frames = std::max(summary.smoothing_max_frames, *window);
          ++summary.smoothing_choices;
        }
        smoother.smooth(*previous, f.index, steps);
        if (smoother.choice_due()) {
          window_choice.start(smoother.tracks_to_choose_by(), session.smoothing.degree,
                              refine.max_smoothing_residual_px,
                              tracker->sliding() ? refine.sliding_noise_scale : 1.0,
                              spacing_mm > 0 && !session.min_spacing_mm);
        }
      }
      const Clock::time_point tracked = Clock::now();
      t.track_ms = ms_between(popped, tracked);
      if (!session.min_spacing_mm && previous && tracker->frames() > kWarmUpFrames) {
        recent_track_ms.push_back(t.track_ms);
        // The first judgement soon: a session that cannot keep up drops frames until it is made.
        const int due = judged_once ? kDensityFrames : kFirstDensityFrames;
        if (static_cast<int>(recent_track_ms.size()) == due) {
          judged_once = true;
          // A frame's work (its tracking here, its strain and mapping on the other thread)
          // against the camera's period. Over budget: landmarks spaced apart, first to nine
          // tenths of their mean distance now (which ends the crowded ones), then a seventh
          // further at a time, up to kMaxSpacingMm (the time that does not depend on the tracks
          // is not saved by fewer); well under it, closer again, to every landmark.
          const double load_ms = median(recent_track_ms) + strain_map_ms.load();
          const double period_ms = 1000.0 / summary.camera_rate_hz;
          const double before = spacing_mm;
          if (load_ms > kBusyShare * period_ms && tracker->live_tracks() > 0) {
            // The area the tracks cover (a print may fill only part of the view).
            double x0 = f.image.width_px, y0 = f.image.height_px, x1 = 0, y1 = 0;
            for (const auto& st : steps) {
              x0 = std::min(x0, st.x_px.back());
              y0 = std::min(y0, st.y_px.back());
              x1 = std::max(x1, st.x_px.back());
              y1 = std::max(y1, st.y_px.back());
            }
            const double area_mm2 = x1 > x0 && y1 > y0
                                        ? (x1 - x0) * (y1 - y0) / (px_per_mm * px_per_mm)
                                        : static_cast<double>(f.image.width_px) *
                                              f.image.height_px / (px_per_mm * px_per_mm);
            spacing_mm = std::min(
                kMaxSpacingMm, spacing_mm == 0 ? 0.9 * std::sqrt(area_mm2 / tracker->live_tracks())
                                               : spacing_mm * 1.15);
          } else if (spacing_mm > 0 && load_ms < kIdleShare * period_ms) {
            spacing_mm /= 1.15;
            if (spacing_mm < 0.15) spacing_mm = 0;
          }
          if (spacing_mm != before) {
            tracker->set_min_spacing_px(spacing_mm * px_per_mm);
            summary.min_spacing_mm = spacing_mm;
            ++summary.spacing_changes;
            summary.max_spacing_mm = std::max(summary.max_spacing_mm, spacing_mm);
            detector->set_idle(spacing_mm > 0);  // only where the session spaced them
          }
          recent_track_ms.clear();
        }
      }
      view_slid = view_slid || tracker->sliding();
      TrackedFrame handed{std::move(f), t, previous, std::move(steps), view_slid, tracked};
      previous = handed.frame.index;
      if (!tracked_frames.push(std::move(handed))) break;
    }
  } catch (...) {
    failure = std::current_exception();
  }
  // The frames handed over are measured and sent before the session ends.
  tracked_frames.close();
  strain_and_mapping.join();
  summary.stopped = stop.load();
  halt = true;
  // Acquisition ends at the source's end or at the stop; a camera read may take a frame time.
  acquisition.join();
  // Frames still waiting when the session stopped were never processed: dropped too.
  std::int64_t left_waiting = 0;
  while (auto left = queue.pop(std::chrono::milliseconds(0))) {
    std::lock_guard lock(dropped_mutex);
    left->image = {};
    dropped.push_back(std::move(*left));
    ++left_waiting;
  }
  report_dropped();
  feeding_done = true;
  feeder.join();
  device.stop();  // the device drops what it holds and ramps every contactor to rest
  // The device's failure first: the processing then only waited for it in vain.
  if (feed_failure) std::rethrow_exception(feed_failure);
  if (strain_failure) std::rethrow_exception(strain_failure);
  if (failure) std::rethrow_exception(failure);
  if (acquisition_failure) std::rethrow_exception(acquisition_failure);

  summary.smoothing_frames = smoother.window_frames();
  if (neighbours) {
    summary.neighbour_sigma_mm = neighbours->sigma_mm();
    summary.neighbour_choices = neighbours->choices();
    summary.neighbour_min_sigma_mm = neighbours->min_chosen_mm();
    summary.neighbour_max_sigma_mm = neighbours->max_chosen_mm();
  }
  summary.frames_in = frames_in;
  summary.frames_driver_stamped = frames_driver_stamped;
  summary.frames_dropped = queue.dropped() + left_waiting;
  summary.device_frames_sent = frames_sent;
  std::vector<double> latency, wait, track, strain, map, send, points;
  for (const auto& t : timings) {
    if (t.dropped) continue;
    latency.push_back(t.latency_ms);
    wait.push_back(t.wait_ms);
    track.push_back(t.track_ms);
    strain.push_back(t.strain_ms);
    map.push_back(t.map_ms);
    send.push_back(t.send_ms);
    points.push_back(t.points);
  }
  if (!latency.empty()) {
    summary.latency_p50_ms = quantile(latency, 0.5);
    summary.latency_p99_ms = quantile(latency, 0.99);
    summary.latency_max_ms = *std::max_element(latency.begin(), latency.end());
    summary.wait_p50_ms = median(wait);
    summary.track_p50_ms = median(track);
    summary.strain_p50_ms = median(strain);
    summary.map_p50_ms = median(map);
    summary.send_p50_ms = median(send);
    summary.median_points = median(points);
  }
  return summary;
}

display::EmulatedDeviceOptions emulated_display_options(const movie::Layout& layout) {
  display::EmulatedDeviceOptions options;
  options.layout = layout;
  options.clock = display::EmulatedClock::real_time;
  options.record_outputs = false;
  return options;
}

std::string format_summary(const LiveSummary& s) {
  std::string out;
  out += fmt::format("frames      {} in, {} processed, {} dropped ({} x {} px at {:g} Hz)\n",
                     s.frames_in, s.frames_processed, s.frames_dropped, s.width_px, s.height_px,
                     s.camera_rate_hz);
  out += fmt::format(
      "latency     p50 {:.2f} ms, p99 {:.2f} ms, max {:.2f} ms (frame available{} "
      "-> its first device frame sent)\n",
      s.latency_p50_ms, s.latency_p99_ms, s.latency_max_ms,
      s.frames_driver_stamped == 0 ? std::string()
      : s.frames_driver_stamped == s.frames_in
          ? std::string(": the driver's timestamp")
          : fmt::format(": the driver's timestamp for {} of {} frames, else arrival",
                        s.frames_driver_stamped, s.frames_in));
  out += fmt::format(
      "stages      medians: queue {:.2f} ms, tracking {:.2f} ms, strain {:.2f} ms, "
      "mapping {:.2f} ms, to the device {:.2f} ms\n",
      s.wait_p50_ms, s.track_p50_ms, s.strain_p50_ms, s.map_p50_ms, s.send_p50_ms);
  out += fmt::format(
      "display     {} device frames sent at {:g} Hz (held between camera frames); "
      "median {:.0f} points tracked a frame\n",
      s.device_frames_sent, s.device_rate_hz, s.median_points);
  const std::string window =
      s.smoothing_frames == 0
          ? std::string("none")
          : fmt::format(
                "each track's step fitted over its last {} positions (a quadratic "
                "looking back; no latency added)",
                s.smoothing_frames);
  out += fmt::format("smoothing   {}{}\n", window,
                     s.smoothing_choices == 0
                         ? std::string()
                         : fmt::format(" at the end; chosen {} time{} by the tracks' own noise, "
                                       "{} to {} positions",
                                       s.smoothing_choices, s.smoothing_choices == 1 ? "" : "s",
                                       s.smoothing_min_frames, s.smoothing_max_frames));
  out += fmt::format(
      "across      {}{}\n",
      s.neighbour_sigma_mm == 0
          ? std::string("none")
          : fmt::format("each step smoothed by its neighbours' in the same frame (a quadratic, "
                        "sigma {:g} mm; no look-ahead)",
                        s.neighbour_sigma_mm),
      s.neighbour_choices == 0
          ? std::string()
          : fmt::format(" at the end; chosen {} time{} by the steps, {:g} to {:g} mm",
                        s.neighbour_choices, s.neighbour_choices == 1 ? "" : "s",
                        s.neighbour_min_sigma_mm, s.neighbour_max_sigma_mm));
  out += fmt::format(
      "density     {}{}\n",
      s.min_spacing_mm == 0 ? std::string("every landmark found")
                            : fmt::format("landmarks at least {:.2f} mm apart", s.min_spacing_mm),
      s.spacing_changes == 0
          ? std::string()
          : fmt::format(" at the end; spaced {} time{} to keep up with the camera (at most {:.2f} "
                        "mm)",
                        s.spacing_changes, s.spacing_changes == 1 ? "" : "s", s.max_spacing_mm));
  if (s.strain_edges_near_gaps > 0) {
    out += fmt::format(
        "contact     {} of {} strain edges left out, at or within {} cell of skin the frames show "
        "out of contact, where the view slid\n",
        s.strain_edges_near_gaps, s.strain_edges, capture::kGapMarginCells);
  }
  return out;
}

}  // namespace tactile::live
