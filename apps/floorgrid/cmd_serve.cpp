// `floorgrid serve DIR-or-DATASET [--dataset D] [--model M] [--host H] [--port P] [--web DIR]
// [--replay [--speed S]]`: the operator's viewer (its page and HTTP API) over an alignment.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/dataset/dataset_loader.hpp"
#include "floorgrid/io/files/atomic_file.hpp"
#include "floorgrid/io/formats/model_io.hpp"
#include "floorgrid/io/formats/pairs_csv.hpp"
#include "floorgrid/io/formats/scans_csv.hpp"
#include "floorgrid/server/pose_replay.hpp"
#include "floorgrid/server/viewer_server.hpp"

namespace floorgrid::app {

namespace {

namespace fs = std::filesystem;

/// The dataset and model files a `serve` argument names: an align output folder (its
/// model.json, the dataset given by --dataset) or a dataset (the model given by --model).
struct ServedFiles {
  fs::path dataset, model, pairs;  ///< pairs: the align folder's pairs.csv (empty: none)
  fs::path scans;                  ///< the align folder's scans.csv (empty: none)
};

/// The dataset an align folder's metrics.json records (empty: none recorded).
fs::path recorded_dataset(const fs::path& folder) {
  const fs::path metrics = folder / "metrics.json";
  if (!fs::exists(metrics))
    return {};
  const nlohmann::json j = nlohmann::json::parse(io::read_whole_file(metrics), nullptr, false);
  if (!j.is_object())
    throw InputError("not a JSON object", metrics.string(), 0, "");
  const auto path = j.find("dataset_path");
  return path != j.end() && path->is_string() ? fs::path(path->get<std::string>()) : fs::path();
}

ServedFiles served_files(const fs::path& target, const std::string& dataset,
                         const std::string& model) {
  if (!fs::exists(target))
    throw InputError("no such file or folder", target.string(), 0, "DIR-or-DATASET");
  ServedFiles files{dataset, model, {}, {}};
  const bool align_folder = fs::is_directory(target) && fs::exists(target / "model.json") &&
                            !fs::exists(target / "dataset.yaml");
  if (align_folder) {
    if (files.model.empty())
      files.model = target / "model.json";
    if (fs::exists(target / "pairs.csv"))
      files.pairs = target / "pairs.csv";
    if (fs::exists(target / "scans.csv"))
      files.scans = target / "scans.csv";
    if (files.dataset.empty())
      files.dataset = recorded_dataset(target);
    if (files.dataset.empty()) {
      throw InputError(
          "an align output folder whose metrics.json names no dataset_path: give the dataset "
          "it aligned with --dataset (the maps the viewer shows)",
          target.string(), 0, "--dataset");
    }
  } else {
    if (!files.dataset.empty()) {
      throw InputError("a dataset is given twice (as DIR-or-DATASET and --dataset)",
                       target.string(), 0, "--dataset");
    }
    files.dataset = target;
    if (files.model.empty()) {
      throw InputError(
          "a dataset: give the model to map with (--model, e.g. an align folder's model.json), "
          "or serve the align output folder itself",
          target.string(), 0, "--model");
    }
  }
  return files;
}

/// The page's files under `web` (the source's web/ folder): public/ at /, and Leaflet from the
/// npm package install-deps put in web/node_modules at /vendor/leaflet/.
std::vector<server::StaticMount> page_files(const fs::path& web) {
  const fs::path page = web / "public", leaflet = web / "node_modules" / "leaflet" / "dist";
  if (!fs::is_directory(page)) {
    fmt::print(stderr, "note: no page at {} (--web): serving the API only\n", page.string());
    return {};
  }
  if (!fs::exists(leaflet / "leaflet.js")) {
    fmt::print(stderr,
               "warning: {} is missing (scripts/install-deps.sh installs it with npm): the page "
               "cannot draw its maps\n",
               leaflet.string());
    return {{"/", page}};
  }
  return {{"/", page}, {"/vendor/leaflet/", leaflet}};
}

/// The run's gridmap track an align folder recorded, for --replay.
std::vector<io::TimedPose> replay_track(const ServedFiles& files, const fs::path& target) {
  if (files.scans.empty()) {
    throw InputError(
        "--replay needs the run's track (scans.csv) of an align folder made from a run; this "
        "has none (a dataset, or an alignment from the maps alone)",
        target.string(), 0, "--replay");
  }
  std::vector<io::TimedPose> track = io::read_grid_track(files.scans);
  if (track.empty()) {
    throw InputError("no scan where the gridmap filter was tracking: nothing to replay",
                     files.scans.string(), 0, "--replay");
  }
  return track;
}

}  // namespace

void add_serve_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "serve", "The operator's viewer: a web page and a JSON API mapping plan <-> grid");
  struct Args {
    std::string target, dataset, model, host = "127.0.0.1", web = FLOORGRID_WEB_DIR;
    int port = 8080;
    bool replay = false;
    double speed = 1.0;
  };
  auto args = std::make_shared<Args>();
  cmd->add_option("DIR-or-DATASET", args->target,
                  "an `align` output folder (with --dataset) or a dataset (with --model)")
      ->required();
  cmd->add_option("--dataset", args->dataset, "the dataset an align folder was made from");
  cmd->add_option("--model", args->model, "model file (default: the align folder's model.json)");
  cmd->add_option("--host", args->host,
                  "address to listen on (default 127.0.0.1: this machine only)");
  cmd->add_option("--port", args->port, "port to listen on (0: any free one)")
      ->check(CLI::Range(0, 65535));
  cmd->add_option("--web", args->web, "folder of the viewer's page (default: the source's web/)");
  auto* replay_flag = cmd->add_flag(
      "--replay", args->replay,
      "feed the run's gridmap poses (the align folder's scans.csv), mapped to the plan, "
      "as the live robot pose, over and over");
  cmd->add_option("--speed", args->speed, "replay speed, times real time (default 1)")
      ->check(CLI::Range(0.01, 1000.0))
      ->needs(replay_flag);
  cmd->callback([args] {
    const ServedFiles files = served_files(args->target, args->dataset, args->model);
    std::vector<io::TimedPose> track;
    if (args->replay)
      track = replay_track(files, args->target);
    std::shared_ptr<const PointMapping> model = io::read_model(files.model);
    const auto d = std::make_shared<const io::LoadedDataset>(io::load_dataset(files.dataset));
    const std::string name = d->manifest.display_name();
    server::ViewerSession session(std::move(model), name, server::viewer_map(d->plan_grid),
                                  server::viewer_map(d->gridmap));
    session.set_layer_renderer(server::dataset_layers(d));
    if (!files.pairs.empty())
      session.set_base_pairs(io::read_pairs_csv(files.pairs));
    server::ServerOptions options;
    options.host = args->host;
    options.port = args->port;
    options.static_files = page_files(args->web);
    server::ViewerServer viewer(session, options);
    int port = 0;
    try {
      port = viewer.bind();
    } catch (const std::runtime_error& e) {
      throw InputError(e.what(), {}, 0, "--port");
    }
    if (args->host != "127.0.0.1" && args->host != "localhost" && args->host != "::1") {
      fmt::print(stderr,
                 "warning: listening on {}: other machines can reach the API (it has no "
                 "authentication)\n",
                 args->host);
    }
    std::unique_ptr<server::PoseReplay> replay;
    if (!track.empty()) {
      server::ReplayOptions replay_options;
      replay_options.speed = args->speed;
      session.set_replay({track.size(), args->speed});
      replay = std::make_unique<server::PoseReplay>(session, std::move(track), replay_options);
      fmt::print("replaying {} gridmap poses of the run at {:g}x as the live pose\n",
                 session.replay()->poses, args->speed);
    }
    fmt::print("serving   {} with model {} at http://{}:{}/ (Ctrl-C stops)\n", name,
               session.model()->name(), args->host, port);
    std::fflush(stdout);
    viewer.listen();
  });
}

}  // namespace floorgrid::app
