#include "floorgrid/server/viewer_server.hpp"

#include <httplib.h>

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "floorgrid/core/error.hpp"

namespace floorgrid::server {

namespace {

void answer_json(httplib::Response& res, const nlohmann::json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

void answer_error(httplib::Response& res, int status, const std::string& message) {
  answer_json(res, {{"error", message}}, status);
}

/// Where a map's picture lies: its pixels, metres per pixel, origin (x, y, yaw) and bounds.
nlohmann::json map_info(const ViewerMap& map) {
  if (map.png.empty())
    return nullptr;
  const GridGeometry& g = map.geometry;
  const Eigen::AlignedBox2d box = g.bounds();
  return {{"width", g.width},
          {"height", g.height},
          {"resolution", g.resolution},
          {"origin", {g.origin.x, g.origin.y, g.origin.theta}},
          {"bounds", {{box.min().x(), box.min().y()}, {box.max().x(), box.max().y()}}}};
}

/// At most this many of the alignment's pairs go to the page (evenly thinned).
constexpr Eigen::Index kMaxBasePairsShown = 20000;

nlohmann::json base_pairs_json(const ReferencePairs& pairs) {
  nlohmann::json out = nlohmann::json::array();
  const Eigen::Index n = pairs.points_in_plan.cols();
  const Eigen::Index shown = std::min(n, kMaxBasePairsShown);
  for (Eigen::Index k = 0; k < shown; ++k) {
    const Eigen::Index i = k * n / shown;
    out.push_back({pairs.points_in_plan(0, i), pairs.points_in_plan(1, i),
                   pairs.points_in_grid(0, i), pairs.points_in_grid(1, i)});
  }
  return out;
}

/// The layers of this session's model now; RequestError 404 when it draws none.
VersionedLayers session_layers(ViewerSession& session) {
  VersionedLayers layers = session.layers();
  if (!layers.layers)
    throw RequestError(404, "this session draws no layers (serve it with a dataset)");
  return layers;
}

/// Runs a handler, answering a RequestError with its status and message.
template <typename Handler>
httplib::Server::Handler guarded(Handler handler) {
  return [handler](const httplib::Request& req, httplib::Response& res) {
    try {
      handler(req, res);
    } catch (const RequestError& e) {
      answer_error(res, e.status(), e.what());
    } catch (const InputError& e) {
      answer_error(res, 400, e.what());  // the library's word on the request's data
    }
  };
}

}  // namespace

struct ViewerServer::Impl {
  Impl(ViewerSession& s, ServerOptions o) : session(s), options(std::move(o)) {}
  ViewerSession& session;
  ServerOptions options;
  httplib::Server http;
};

ViewerServer::ViewerServer(ViewerSession& session, ServerOptions options)
    : impl_(std::make_unique<Impl>(session, std::move(options))) {
  Impl& s = *impl_;
  s.http.set_payload_max_length(s.options.max_body_bytes);
  const auto threads = static_cast<std::size_t>(std::max(1, s.options.threads));
  s.http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  s.http.set_keep_alive_timeout(2);
  s.http.set_tcp_nodelay(true);  // an answer written in parts must not wait for an ACK
  s.http.set_read_timeout(10, 0);
  s.http.set_write_timeout(10, 0);
  s.http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        std::string message = "internal error";
        try {
          std::rethrow_exception(std::move(error));
        } catch (const std::exception& e) {
          message += std::string(": ") + e.what();
        } catch (...) {
        }
        answer_error(res, 500, message);
      });
  s.http.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty())
      return;  // a handler's own answer
    // cpp-httplib parses a form-encoded body itself and refuses one over 8 KiB (compiled in):
    // the JSON API's usual mistake (curl -d without a Content-Type), said so.
    const bool form =
        req.get_header_value("Content-Type").starts_with("application/x-www-form-urlencoded");
    const std::string message = res.status == 413 && form
                                    ? "a body sent as application/x-www-form-urlencoded is "
                                      "limited to 8 KiB: send JSON with Content-Type: "
                                      "application/json (curl -H 'Content-Type: "
                                      "application/json' -d @points.json)"
                                : res.status == 413 ? "the request body is too large"
                                : res.status == 404 ? "no such path: " + req.path
                                                    : "bad request";
    answer_error(res, res.status, message);
  });

  const RequestLimits limits = s.options.limits;
  s.http.Get("/api/info", guarded([&session](const httplib::Request&, httplib::Response& res) {
               nlohmann::json replay = nullptr;
               if (const std::optional<ReplayInfo>& r = session.replay())
                 replay = {{"poses", r->poses}, {"speed", r->speed}};
               answer_json(
                   res, {{"dataset", session.dataset()},
                         {"model", session.model()->name()},
                         {"model_version", session.model_version()},
                         {"models", mapping_model_names()},
                         {"plan", map_info(session.plan())},
                         {"grid", map_info(session.grid())},
                         {"layers",
                          {{"overlay", session.has_layers()}, {"heatmap", session.has_layers()}}},
                         {"replay", replay},
                         {"robot_pose_sequence", session.robot_pose().sequence}});
             }));
  for (const char* which : {"plan", "grid"}) {
    const ViewerMap& map = std::string(which) == "plan" ? session.plan() : session.grid();
    s.http.Get(std::string("/api/maps/") + which + ".png", [&map, which](const httplib::Request&,
                                                                         httplib::Response& res) {
      if (map.png.empty())
        return answer_error(res, 404, std::string("this session has no ") + which + " map");
      res.set_content(map.png, "image/png");
    });
  }
  s.http.Post("/api/map",
              guarded([&session, limits](const httplib::Request& req, httplib::Response& res) {
                const nlohmann::json request = parse_request(req.body);
                const std::shared_ptr<const PointMapping> model = session.model();
                answer_json(res, map_points(request, *model, limits));
              }));
  s.http.Get("/api/robot_pose",
             guarded([&session](const httplib::Request&, httplib::Response& res) {
               const RobotPose r = session.robot_pose();
               nlohmann::json body{{"sequence", r.sequence}};
               if (r.sequence > 0) {
                 body["x"] = r.pose_in_grid.x;
                 body["y"] = r.pose_in_grid.y;
                 body["theta"] = r.pose_in_grid.theta;
                 body["plan"] = mapped_point_json(*session.model(), r.pose_in_grid, true, false);
               }
               answer_json(res, body);
             }));
  s.http.Post("/api/robot_pose",
              guarded([&session](const httplib::Request& req, httplib::Response& res) {
                const Pose2 pose = parse_robot_pose(parse_request(req.body));
                answer_json(res, {{"sequence", session.post_robot_pose(pose)}});
              }));
  s.http.Get("/api/pairs", guarded([&session](const httplib::Request& req, httplib::Response& res) {
               nlohmann::json pairs = nlohmann::json::array();
               for (const ManualPair& p : session.manual_pairs()) {
                 pairs.push_back({{"id", p.id},
                                  {"plan", {p.point_in_plan.x(), p.point_in_plan.y()}},
                                  {"grid", {p.point_in_grid.x(), p.point_in_grid.y()}}});
               }
               nlohmann::json body{{"pairs", pairs}, {"base_pairs", session.base_pairs().size()}};
               if (req.has_param("base")) {
                 const std::string base = req.get_param_value("base");
                 if (base != "0" && base != "1")
                   throw RequestError(400, "'base' must be 0 or 1 (got \"" + base + "\")");
                 if (base == "1")
                   body["base"] = base_pairs_json(session.base_pairs());
               }
               answer_json(res, body);
             }));
  s.http.Post("/api/pairs",
              guarded([&session](const httplib::Request& req, httplib::Response& res) {
                const PairRequest p = parse_pair(parse_request(req.body));
                answer_json(res, {{"id", session.add_pair(p.point_in_plan, p.point_in_grid)}}, 201);
              }));
  s.http.Delete(R"(/api/pairs/(\d{1,18}))",
                guarded([&session](const httplib::Request& req, httplib::Response& res) {
                  const std::uint64_t id = std::stoull(req.matches[1].str());
                  if (!session.delete_pair(id))
                    throw RequestError(404, "no manual pair " + std::to_string(id));
                  answer_json(res, {{"deleted", id}});
                }));
  s.http.Post("/api/fit", guarded([&session](const httplib::Request& req, httplib::Response& res) {
                MappingOptions fit;
                fit.model = parse_fit_model(parse_request(req.body));
                const RefitSummary r = session.refit(fit);
                answer_json(res, {{"model", r.model},
                                  {"pairs", r.pairs},
                                  {"rms_m", r.rms_m},
                                  {"cv_error_m", r.cv_error_m ? nlohmann::json(*r.cv_error_m)
                                                              : nlohmann::json(nullptr)},
                                  {"has_std_m", r.has_std},
                                  {"seconds", r.seconds}});
              }));
  s.http.Get("/api/overlay.png",
             guarded([&session](const httplib::Request&, httplib::Response& res) {
               const VersionedLayers layers = session_layers(session);
               if (layers.layers->overlay_png.empty())
                 throw RequestError(404, "this session has no overlay");
               res.set_header("Cache-Control", "no-cache");
               res.set_content(layers.layers->overlay_png, "image/png");
             }));
  s.http.Get("/api/heatmap", guarded([&session](const httplib::Request&, httplib::Response& res) {
               const VersionedLayers layers = session_layers(session);
               nlohmann::json list = nlohmann::json::array();
               for (const HeatLayer& h : layers.layers->heat) {
                 list.push_back({{"kind", h.kind},
                                 {"quantity", h.quantity},
                                 {"clip_m", h.clip_m},
                                 {"url", "/api/heatmap.png?kind=" + h.kind +
                                             "&v=" + std::to_string(layers.model_version)}});
               }
               answer_json(res, {{"model_version", layers.model_version},
                                 {"model", layers.model},
                                 {"seconds", layers.layers->seconds},
                                 {"layers", list}});
             }));
  s.http.Get("/api/heatmap.png",
             guarded([&session](const httplib::Request& req, httplib::Response& res) {
               const VersionedLayers layers = session_layers(session);
               const std::string kind =
                   req.has_param("kind") ? req.get_param_value("kind") : std::string("std");
               std::string known;
               for (const HeatLayer& h : layers.layers->heat) {
                 if (h.kind == kind) {
                   res.set_header("Cache-Control", "no-cache");
                   return res.set_content(h.png, "image/png");
                 }
                 known += (known.empty() ? "" : ", ") + h.kind;
               }
               throw RequestError(
                   404, "no heat map of kind '" + kind + "' (this session has " + known + ")");
             }));
  for (const StaticMount& mount : s.options.static_files) {
    if (!s.http.set_mount_point(mount.prefix, mount.folder.string()))
      throw std::runtime_error("the web folder " + mount.folder.string() + " is not a folder");
  }
}

ViewerServer::~ViewerServer() {
  stop();
}

int ViewerServer::bind() {
  Impl& s = *impl_;
  const int port = s.options.port == 0 ? s.http.bind_to_any_port(s.options.host)
                   : s.http.bind_to_port(s.options.host, s.options.port) ? s.options.port
                                                                         : -1;
  if (port < 0) {
    throw std::runtime_error("cannot listen on " + s.options.host + ":" +
                             std::to_string(s.options.port));
  }
  return port;
}

void ViewerServer::listen() {
  impl_->http.listen_after_bind();
}

void ViewerServer::stop() {
  if (impl_ && impl_->http.is_running())
    impl_->http.stop();
}

}  // namespace floorgrid::server
