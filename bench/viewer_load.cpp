// Load test of the viewer's API on loopback: N requests of P points each (POST /api/map, from
// the plan and from the grid in turn) from C concurrent clients, each on its own kept-alive
// connection, against an in-process `floorgrid serve` server. Prints the throughput and the
// latency percentiles, and fails (exit 1) on any error or on an answer that is not the model's.
//
//   viewer_load [--align DIR | --fit MODEL] [--requests 10000] [--clients 8] [--points 100]
//
// With --align it maps with an align folder's model.json, at points over its pairs.csv's
// extent; without, with MODEL (default tps) fitted to 1,000 pairs of a smooth warp. The
// server's own cost shows with a cheap model (--fit gt); the models' in mapping_bench.
#include <fmt/format.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/mapping/mapping_factory.hpp"
#include "floorgrid/server/viewer_server.hpp"

// Last: httplib.h brings <resolv.h>, whose `_res` macro breaks Eigen's headers after it.
#include <httplib.h>  // NOLINT(llvm-include-order)

namespace {

using floorgrid::PointMapping;
using Clock = std::chrono::steady_clock;

struct Settings {
  std::string align;
  std::string fit = "tps";
  int requests = 10'000;
  int clients = 8;
  int points = 100;
};

Settings parse(int argc, char** argv) {
  Settings s;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) {
      fmt::print(stderr, "viewer_load: {} needs a value\n", arg);
      std::exit(2);
    }
    const std::string value = argv[++i];
    if (arg == "--align") {
      s.align = value;
    } else if (arg == "--fit") {
      s.fit = value;
    } else if (arg == "--requests" || arg == "--clients" || arg == "--points") {
      const int n = std::atoi(value.c_str());
      if (n <= 0) {
        fmt::print(stderr, "viewer_load: {} must be a positive number (got {})\n", arg, value);
        std::exit(2);
      }
      (arg == "--requests" ? s.requests : arg == "--clients" ? s.clients : s.points) = n;
    } else {
      fmt::print(stderr, "viewer_load: unknown option {}\n", arg);
      std::exit(2);
    }
  }
  return s;
}

/// A smooth warp of a 60 x 40 m floor: the default model's truth.
Eigen::Vector2d warp(const Eigen::Vector2d& p) {
  return Eigen::Vector2d(1.02 * p.x() + 0.3 * std::sin(p.y() / 7.0) - 4.0,
                         0.98 * p.y() + 0.2 * std::cos(p.x() / 9.0) + 2.0);
}

floorgrid::ReferencePairs warp_pairs() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> x(0.0, 60.0), y(0.0, 40.0);
  floorgrid::ReferencePairs pairs;
  pairs.points_in_plan.resize(2, 1000);
  pairs.points_in_grid.resize(2, 1000);
  for (Eigen::Index i = 0; i < 1000; ++i) {
    pairs.points_in_plan.col(i) = Eigen::Vector2d(x(rng), y(rng));
    pairs.points_in_grid.col(i) = warp(pairs.points_in_plan.col(i));
  }
  return pairs;
}

std::shared_ptr<const PointMapping> fitted(const std::string& name,
                                           const floorgrid::ReferencePairs& pairs) {
  floorgrid::MappingOptions options;
  options.model = name;
  std::shared_ptr<PointMapping> model = floorgrid::make_mapping(options);
  model->fit(pairs);
  return model;
}

Eigen::AlignedBox2d extent(const Eigen::Matrix2Xd& points) {
  return Eigen::AlignedBox2d(points.rowwise().minCoeff(), points.rowwise().maxCoeff());
}

/// Request bodies: points spread over the pairs' extent, from the plan and from the grid.
std::vector<std::string> request_bodies(int count, int points,
                                        const floorgrid::ReferencePairs& pairs,
                                        std::vector<Eigen::Matrix2Xd>& sent) {
  const Eigen::AlignedBox2d boxes[] = {extent(pairs.points_in_plan), extent(pairs.points_in_grid)};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<std::string> bodies;
  for (int b = 0; b < count; ++b) {
    const bool from_plan = b % 2 == 0;
    const Eigen::AlignedBox2d& box = boxes[from_plan ? 0 : 1];
    Eigen::Matrix2Xd p(2, points);
    std::string body = fmt::format(R"({{"from": "{}", "points": [)", from_plan ? "plan" : "grid");
    for (int i = 0; i < points; ++i) {
      p.col(i) = box.min() + Eigen::Vector2d(u(rng), u(rng)).cwiseProduct(box.sizes());
      body += fmt::format("{}[{:.17g}, {:.17g}]", i ? ", " : "", p(0, i), p(1, i));
    }
    bodies.push_back(body + "]}");
    sent.push_back(p);
  }
  return bodies;
}

double percentile(std::vector<double> v, double q) {
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}

}  // namespace

int main(int argc, char** argv) {
  const Settings settings = parse(argc, argv);
  const floorgrid::ReferencePairs pairs =
      settings.align.empty() ? warp_pairs()
                             : floorgrid::io::read_pairs_csv(settings.align + "/pairs.csv");
  const std::shared_ptr<const PointMapping> model =
      settings.align.empty() ? fitted(settings.fit, pairs)
                             : floorgrid::io::read_model(settings.align + "/model.json");
  floorgrid::server::ViewerSession session(model, "load test");
  floorgrid::server::ServerOptions options;
  options.port = 0;
  floorgrid::server::ViewerServer server(session, options);
  const int port = server.bind();
  std::thread listening([&server] { server.listen(); });

  constexpr int kDistinct = 64;  // distinct bodies, sent round-robin
  std::vector<Eigen::Matrix2Xd> sent;
  const std::vector<std::string> bodies = request_bodies(kDistinct, settings.points, pairs, sent);

  std::atomic<int> next = 0, errors = 0, wrong = 0;
  std::vector<std::vector<double>> latencies(static_cast<std::size_t>(settings.clients));
  const auto start = Clock::now();
  std::vector<std::thread> clients;
  for (int c = 0; c < settings.clients; ++c) {
    clients.emplace_back([&, c] {
      httplib::Client client("127.0.0.1", port);
      client.set_keep_alive(true);
      client.set_tcp_nodelay(true);
      for (int k = next++; k < settings.requests; k = next++) {
        const std::string& body = bodies[static_cast<std::size_t>(k % kDistinct)];
        const auto sent_at = Clock::now();
        const httplib::Result r = client.Post("/api/map", body, "application/json");
        latencies[static_cast<std::size_t>(c)].push_back(
            std::chrono::duration<double, std::milli>(Clock::now() - sent_at).count());
        if (!r || r->status != 200) {
          ++errors;
          continue;
        }
        // Every 50th answer is checked against the model itself.
        if (k % 50 != 0)
          continue;
        const nlohmann::json answer = nlohmann::json::parse(r->body, nullptr, false);
        const Eigen::Matrix2Xd& p = sent[static_cast<std::size_t>(k % kDistinct)];
        if (!answer.is_object() || answer["points"].size() != static_cast<std::size_t>(p.cols())) {
          ++wrong;
          continue;
        }
        const bool from_plan = k % kDistinct % 2 == 0;
        for (Eigen::Index i = 0; i < p.cols(); ++i) {
          const floorgrid::MappedPoint m =
              from_plan ? model->map_forward(p.col(i)) : model->map_inverse(p.col(i));
          const nlohmann::json& a = answer["points"][static_cast<std::size_t>(i)];
          if (m.flag == floorgrid::MapFlag::not_invertible
                  ? !a["x"].is_null()
                  : std::abs(a["x"].get<double>() - m.point.x()) > 1e-9) {
            ++wrong;
            break;
          }
        }
      }
    });
  }
  for (std::thread& t : clients)
    t.join();
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  server.stop();
  listening.join();

  std::vector<double> all;
  for (const std::vector<double>& l : latencies)
    all.insert(all.end(), l.begin(), l.end());
  fmt::print("viewer_load: model {}, {} requests x {} points from {} clients on loopback\n",
             model->name(), settings.requests, settings.points, settings.clients);
  fmt::print("  {:.2f} s, {:.0f} requests/s ({:.0f} points/s)\n", seconds,
             settings.requests / seconds, settings.requests * settings.points / seconds);
  fmt::print("  latency p50 {:.2f} ms, p99 {:.2f} ms, max {:.2f} ms\n", percentile(all, 0.5),
             percentile(all, 0.99), percentile(all, 1.0));
  fmt::print("  errors {}, answers unlike the model {}\n", errors.load(), wrong.load());
  return errors == 0 && wrong == 0 ? 0 : 1;
}
