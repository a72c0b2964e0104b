#pragma once

#include <cstddef>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "floorgrid/server/connection_limits.hpp"
#include "floorgrid/server/map_request.hpp"
#include "floorgrid/server/plan_layers_request.hpp"
#include "floorgrid/server/viewer_session.hpp"

namespace floorgrid::server {

/// A folder whose files are served under a URL prefix (nothing outside it).
struct StaticMount {
  std::string prefix;            ///< "/" or "/vendor/leaflet/"
  std::filesystem::path folder;  ///< must exist
};

/// Where and how the viewer's server listens, and what it takes on at once.
struct ServerOptions {
  std::string host = "127.0.0.1";         ///< loopback unless told otherwise
  int port = 8080;                        ///< 0: any free port (bind() says which)
  std::vector<StaticMount> static_files;  ///< the page's files (none: the API alone)
  std::size_t max_body_bytes = 8u << 20;  ///< a POST /api/map body larger gets 413
  /// A body of the other routes (a pair, a pose, a model's name) larger gets 413.
  std::size_t max_small_body_bytes = 64u << 10;
  /// Threads answering requests. A kept-alive connection holds one while it lasts: a browser
  /// keeps up to 6, so a pool of 8 (cpp-httplib's default) starves a second page or client;
  /// a client that sends its headers slowly holds one until connection.header_timeout_s.
  int threads = 64;
  /// POST /api/map requests with a body over large_request_bytes (or of unknown length)
  /// answered at once; another gets 503 with Retry-After. Each holds at most max_body_bytes
  /// and 32 bytes a point while it is answered.
  std::size_t large_requests = 4;
  std::size_t large_request_bytes = 64u << 10;  ///< see large_requests
  /// Answers of more points than this are sent while they are made (chunked), not held whole.
  std::size_t streamed_points = 2000;
  /// A body of the zones and waypoints routes (a loaded GeoJSON or CSV file) larger gets 413.
  std::size_t max_layers_body_bytes = 2u << 20;
  /// Zones and waypoints requests answered at once (each maps a boundary and draws a mask on
  /// the gridmap's grid: up to a second); another gets 503 with Retry-After.
  std::size_t layer_requests = 2;
  ConnectionLimits connection;  ///< how long and how much a connection may take
  RequestLimits limits;         ///< what one request may ask for
  PlanLayersLimits layers;      ///< what one zones or waypoints request may ask for
};

/// The viewer's HTTP server (cpp-httplib): the JSON API over a ViewerSession and the static
/// files of the web root (nothing outside it). Every bad request gets a 4xx status and
/// {"error": message naming the field}; bytes of the request it repeats are written %XX.
///   GET  /api/info         {"dataset", "model", "model_version", "models", "plan", "grid"
///                          (pixels, resolution, origin, bounds), "layers", "replay",
///                          "robot_pose_sequence"}
///   GET  /api/maps/plan.png, /api/maps/grid.png   the maps' pictures (info's bounds)
///   POST /api/map          see map_points
///   GET  /api/robot_pose   {"sequence", "x", "y", "theta", "plan": {"x", "y", "theta",
///                          "std_m", "nearest_pair_m", "flag", "extrapolated"}} (sequence 0:
///                          none yet, and no pose)
///   POST /api/robot_pose   {"x", "y", "theta"} in the grid frame -> {"sequence"}
///   GET  /api/pairs        {"pairs": [{"id", "plan", "grid"}], "base_pairs"}: the manual ones;
///                          ?base=1 adds "base": [[plan x, y, grid x, y]] (at most 20,000)
///   POST /api/pairs        {"plan": [x, y], "grid": [x, y]} -> 201 {"id"}
///   DELETE /api/pairs/ID   {"deleted"}, 404 when there is no such pair
///   POST /api/fit          {"model"} -> {"model", "pairs", "rms_m", "cv_error_m", "has_std_m",
///                          "seconds"}: fitted (and cross-validated) to the
///                          alignment's and the manual pairs, then swapped in
///   GET  /api/overlay.png  the plan's walls through the model on the gridmap's pixels
///   GET  /api/heatmap      {"model_version", "model", "seconds", "layers": [{"kind",
///                          "quantity", "clip_m", "url"}]}
///   GET  /api/heatmap.png?kind=error|std   a heat map on the plan's pixels
///   POST /api/zones        zones (GeoJSON, plan metres) mapped onto the gridmap with their
///                          margin and the mask's picture (zones_answer)
///   POST /api/zones/nav2   the same zones as nav2 filter-mask files (zones_nav2_answer)
///   POST /api/waypoints    waypoints (GeoJSON or CSV) mapped, with their nav2 YAML
///                          (waypoints_answer)
class ViewerServer {
 public:
  /// A server over `session` (which must outlive it).
  ViewerServer(ViewerSession& session, ServerOptions options);
  ~ViewerServer();
  ViewerServer(const ViewerServer&) = delete;
  ViewerServer& operator=(const ViewerServer&) = delete;

  /// Binds to options.host and options.port; returns the port bound. std::runtime_error when
  /// the address cannot be bound.
  int bind();
  /// Answers requests until stop() (call after bind(), on its own thread if need be).
  void listen();
  /// Stops listen() (from any thread).
  void stop();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace floorgrid::server
