// The emulator window as play_anywhere's back end; see viewer.hpp.
#include <fmt/format.h>

#include "tactile/common/stop_signals.hpp"
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/viewer.hpp"

namespace tactile::display {

PlayBackends with_window(PlayBackends backends) {
  backends.screen = screen_available;
  backends.play_in_window = [](const movie::TactileMovie& movie, const ResolvedPlay& request,
                               const Say& say, PlayResult& result) {
    ViewerOptions viewer;
    viewer.loop = request.loops > 1;
    viewer.play.stop_fd = request.stop_fd;
    const ViewerResult r = run_viewer(movie, viewer);
    if (stop_requested(request.stop_fd)) {
      result.stopped = true;
      say(fmt::format("play: window closed by a stop request at frame {} of {} ({} drawn)\n",
                      r.last_movie_frame + 1, r.shown_frame_count, r.frames_drawn));
    }
  };
  return backends;
}

}  // namespace tactile::display
