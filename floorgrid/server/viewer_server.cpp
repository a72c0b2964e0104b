#include "floorgrid/server/viewer_server.hpp"

#include <algorithm>
#include <functional>
#include <optional>
#include <stdexcept>
#include <utility>

#include "floorgrid/core/error.hpp"
#include "floorgrid/server/map_request_parser.hpp"
#include "floorgrid/server/printable_text.hpp"
#include "floorgrid/server/request_slots.hpp"
// Last: cpp-httplib's <httplib.h> brings <resolv.h>, whose `_res` macro breaks Eigen's headers
// after it.
#include "floorgrid/server/http_answers.hpp"  // NOLINT(llvm-include-order)
#include "floorgrid/server/request_body.hpp"  // NOLINT(llvm-include-order)

namespace floorgrid::server {

namespace {

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

/// A handler run by answering_errors.
template <typename Handler>
httplib::Server::Handler guarded(Handler handler) {
  return [handler](const httplib::Request& req, httplib::Response& res) {
    answering_errors(res, [&] { handler(req, res); });
  };
}

/// A handler of a POST's body (at most `limit` bytes; see read_body) run by answering_errors.
template <typename Handler>
httplib::Server::HandlerWithContentReader with_body(std::size_t limit, Handler handler) {
  return [limit, handler](const httplib::Request& req, httplib::Response& res,
                          const httplib::ContentReader& reader) {
    answering_errors(res, [&] { handler(req, res, read_body(req, res, reader, limit)); });
  };
}

/// The routes a method has (a request elsewhere is refused before its body is read).
bool is_route(const std::string& method, const std::string& path) {
  if (method == "POST")
    return path == "/api/map" || path == "/api/robot_pose" || path == "/api/pairs" ||
           path == "/api/fit" || path == "/api/zones" || path == "/api/zones/nav2" ||
           path == "/api/waypoints";
  if (method == "DELETE")
    return path.starts_with("/api/pairs/");
  return method == "GET" || method == "HEAD" || method == "OPTIONS";
}

/// Whether `req` comes with a body.
bool has_body(const httplib::Request& req) {
  return req.has_header("Transfer-Encoding") ||
         (req.has_header("Content-Length") && req.get_header_value("Content-Length") != "0");
}

/// Checks a request once its headers are read, before its body: a NUL or other control byte
/// in the path (a file name cut short at it) gets 400, a method or path without a route 404 or
/// 405 (cpp-httplib would read such a body whole first).
httplib::Server::HandlerResponse check_request_head(const httplib::Request& req,
                                                    httplib::Response& res) {
  if (HttpConnection* connection = HttpConnection::current())
    connection->begin_body();
  const auto refuse = [&](int status, const std::string& message) {
    if (has_body(req))
      close_after(res);
    answer_error(res, status, message);
    return httplib::Server::HandlerResponse::Handled;
  };
  if (has_control_byte(req.path)) {
    return refuse(400, "the path holds a NUL or another control byte: " + printable_text(req.path));
  }
  if (!is_route(req.method, req.path)) {
    if (req.method == "POST" || req.method == "DELETE")
      return refuse(404, "no such path: " + printable_text(req.path));
    return refuse(405, "the method " + printable_text(req.method) + " is not served");
  }
  if (req.method == "DELETE" && has_body(req))
    return refuse(400, "a DELETE takes no body");
  return httplib::Server::HandlerResponse::Unhandled;
}

}  // namespace

struct ViewerServer::Impl {
  Impl(ViewerSession& s, ServerOptions o)
      : session(s),
        options(std::move(o)),
        large(options.large_requests),
        layer_slots(options.layer_requests),
        http(options.connection) {}
  ViewerSession& session;
  ServerOptions options;
  RequestSlots large;        ///< POST /api/map requests over options.large_request_bytes
  RequestSlots layer_slots;  ///< zones and waypoints requests
  LimitedHttpServer http;
};

namespace {

/// The session's maps as the zones and waypoints routes check against them; RequestError 404
/// when the session has no gridmap (the mask takes its grid).
PlanLayersContext plan_layers_context(const ViewerSession& session,
                                      const PlanLayersLimits& limits) {
  if (session.grid().png.empty())
    throw RequestError(404, "this session has no gridmap: zones and waypoints map onto it");
  PlanLayersContext context;
  context.gridmap = session.grid().geometry;
  if (!session.plan().png.empty())
    context.plan_bounds = session.plan().geometry.bounds();
  context.limits = limits;
  return context;
}

/// POST /api/zones, /api/zones/nav2 and /api/waypoints: a body of at most
/// max_layers_body_bytes, at most layer_requests at once (503 beyond), the model of the
/// request's start for all of it.
void add_plan_layer_routes(LimitedHttpServer& http, ViewerSession& session,
                           const ServerOptions& options, RequestSlots& slots) {
  using Answer = std::function<nlohmann::json(const nlohmann::json&, const PointMapping&,
                                              const PlanLayersContext&)>;
  const auto route = [&](const char* path, Answer answer) {
    http.Post(path, [&session, &options, &slots, answer](const httplib::Request& req,
                                                         httplib::Response& res,
                                                         const httplib::ContentReader& reader) {
      answering_errors(res, [&] {
        std::optional<RequestSlots::Slot> slot = slots.try_take();
        if (!slot) {
          drop_body(req, res, reader, options.max_layers_body_bytes);
          throw RequestError(503, "busy: " + std::to_string(slots.slots()) +
                                      " zones or waypoints requests are being answered; try "
                                      "again in a moment (Retry-After)");
        }
        const nlohmann::json body =
            parse_request(read_body(req, res, reader, options.max_layers_body_bytes));
        const PlanLayersContext context = plan_layers_context(session, options.layers);
        const std::shared_ptr<const PointMapping> model = session.model();
        answer_json(res, answer(body, *model, context));
      });
    });
  };
  route("/api/zones", [](const nlohmann::json& body, const PointMapping& model,
                         const PlanLayersContext& context) {
    return zones_answer(parse_zones_request(body, context), model, context);
  });
  route("/api/zones/nav2", [](const nlohmann::json& body, const PointMapping& model,
                              const PlanLayersContext& context) {
    return zones_nav2_answer(parse_zones_request(body, context), model, context);
  });
  route("/api/waypoints", waypoints_answer);
}

}  // namespace

ViewerServer::ViewerServer(ViewerSession& session, ServerOptions options)
    : impl_(std::make_unique<Impl>(session, std::move(options))) {
  Impl& s = *impl_;
  s.http.set_payload_max_length(s.options.max_body_bytes);
  const auto threads = static_cast<std::size_t>(std::max(1, s.options.threads));
  s.http.new_task_queue = [threads] { return new httplib::ThreadPool(threads); };
  s.http.set_tcp_nodelay(true);  // an answer written in parts must not wait for an ACK
  // Timeouts: s.options.connection, kept by LimitedHttpServer's connections.
  s.http.set_exception_handler(
      [](const httplib::Request&, httplib::Response& res, std::exception_ptr error) {
        std::string message = "internal error";
        try {
          std::rethrow_exception(std::move(error));
        } catch (const std::exception& e) {
          message += ": " + printable_text(e.what(), 400);
        } catch (...) {
        }
        answer_error(res, 500, message);
      });
  s.http.set_pre_routing_handler(check_request_head);
  s.http.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (!res.body.empty() || res.content_length_ > 0)
      return;  // a handler's own answer
    if (const HttpConnection* connection = HttpConnection::current()) {
      if (connection->timed_out()) {
        res.status = 408;
        return answer_error(res, 408, "the request's line and headers did not come in time");
      }
      if (connection->headers_too_large()) {
        res.status = 431;
        return answer_error(res, 431, "the request's line and headers are too large");
      }
    }
    const std::string message = res.status == 413   ? "the request body is too large"
                                : res.status == 414 ? "the request's path is too long"
                                : res.status == 404 ? "no such path: " + printable_text(req.path)
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
      answer_bytes(res, map.png, "image/png");
    });
  }
  s.http.Post("/api/map", [&s](const httplib::Request& req, httplib::Response& res,
                               const httplib::ContentReader& reader) {
    answering_errors(res, [&] {
      // A large body takes a slot first: the slots bound the memory of the bodies and points
      // held at once (a body of unknown length counts as large).
      std::optional<RequestSlots::Slot> slot;
      const std::optional<std::size_t> length = body_length(req);
      if (!length || *length > s.options.large_request_bytes) {
        slot = s.large.try_take();
        if (!slot) {
          drop_body(req, res, reader, s.options.max_body_bytes);
          throw RequestError(503, "busy: " + std::to_string(s.large.slots()) +
                                      " large requests are being answered; try again in a "
                                      "moment (Retry-After)");
        }
      }
      std::shared_ptr<const PointMapping> model = s.session.model();
      MapRequest request = parse_map_request(read_body(req, res, reader, s.options.max_body_bytes),
                                             s.options.limits, model->name());
      answer_mapped_points(res, std::move(model), std::move(request), std::move(slot),
                           s.options.streamed_points);
    });
  });
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
  const std::size_t small_body = s.options.max_small_body_bytes;
  s.http.Post("/api/robot_pose",
              with_body(small_body, [&session](const httplib::Request&, httplib::Response& res,
                                               const std::string& body) {
                const Pose2 pose = parse_robot_pose(parse_request(body));
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
                 if (base != "0" && base != "1") {
                   throw RequestError(
                       400, "'base' must be 0 or 1 (got \"" + printable_text(base) + "\")");
                 }
                 if (base == "1")
                   body["base"] = base_pairs_json(session.base_pairs());
               }
               answer_json(res, body);
             }));
  s.http.Post("/api/pairs", with_body(small_body, [&session, limits](const httplib::Request&,
                                                                     httplib::Response& res,
                                                                     const std::string& body) {
                const PairRequest p = parse_pair(parse_request(body));
                check_pair_near_maps(p, session.pair_bounds(), limits);
                answer_json(res, {{"id", session.add_pair(p.point_in_plan, p.point_in_grid)}}, 201);
              }));
  s.http.Delete(R"(/api/pairs/(\d{1,18}))",
                guarded([&session](const httplib::Request& req, httplib::Response& res) {
                  const std::uint64_t id = std::stoull(req.matches[1].str());
                  if (!session.delete_pair(id))
                    throw RequestError(404, "no manual pair " + std::to_string(id));
                  answer_json(res, {{"deleted", id}});
                }));
  s.http.Post(
      "/api/fit", with_body(small_body, [&session](const httplib::Request&, httplib::Response& res,
                                                   const std::string& body) {
        MappingOptions fit;
        fit.model = parse_fit_model(parse_request(body));
        const RefitSummary r = session.refit(fit);
        answer_json(res, {{"model", r.model},
                          {"pairs", r.pairs},
                          {"rms_m", r.rms_m},
                          {"cv_error_m",
                           r.cv_error_m ? nlohmann::json(*r.cv_error_m) : nlohmann::json(nullptr)},
                          {"has_std_m", r.has_std},
                          {"seconds", r.seconds}});
      }));
  s.http.Get("/api/overlay.png",
             guarded([&session](const httplib::Request&, httplib::Response& res) {
               const VersionedLayers layers = session_layers(session);
               if (layers.layers->overlay_png.empty())
                 throw RequestError(404, "this session has no overlay");
               res.set_header("Cache-Control", "no-cache");
               answer_bytes(res, layers.layers->overlay_png, "image/png", layers.layers);
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
                   return answer_bytes(res, h.png, "image/png", layers.layers);
                 }
                 known += (known.empty() ? "" : ", ") + h.kind;
               }
               throw RequestError(404, "no heat map of kind '" + printable_text(kind) +
                                           "' (this session has " + known + ")");
             }));
  add_plan_layer_routes(s.http, s.session, s.options, s.layer_slots);
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
