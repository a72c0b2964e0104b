// `floorgrid serve DIR-or-DATASET [--dataset D] [--model M] [--host H] [--port P] [--web DIR]`:
// the operator's viewer (its HTTP API and static files) over an alignment.
#include <fmt/format.h>

#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>

#include "apps/floorgrid/commands.hpp"
#include "floorgrid/core/error.hpp"
#include "floorgrid/io/atomic_file.hpp"
#include "floorgrid/io/dataset_loader.hpp"
#include "floorgrid/io/model_io.hpp"
#include "floorgrid/io/pairs_csv.hpp"
#include "floorgrid/server/viewer_server.hpp"

namespace floorgrid::app {

namespace {

namespace fs = std::filesystem;

/// The dataset and model files a `serve` argument names: an align output folder (its
/// model.json, the dataset given by --dataset) or a dataset (the model given by --model).
struct ServedFiles {
  fs::path dataset, model, pairs;  ///< pairs: the align folder's pairs.csv (empty: none)
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
  ServedFiles files{dataset, model, {}};
  const bool align_folder = fs::is_directory(target) && fs::exists(target / "model.json") &&
                            !fs::exists(target / "dataset.yaml");
  if (align_folder) {
    if (files.model.empty())
      files.model = target / "model.json";
    if (fs::exists(target / "pairs.csv"))
      files.pairs = target / "pairs.csv";
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

}  // namespace

void add_serve_command(CLI::App& root) {
  auto* cmd = root.add_subcommand(
      "serve", "The operator's viewer: a web page and a JSON API mapping plan <-> grid");
  struct Args {
    std::string target, dataset, model, host = "127.0.0.1", web = FLOORGRID_WEB_DIR;
    int port = 8080;
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
  cmd->callback([args] {
    const ServedFiles files = served_files(args->target, args->dataset, args->model);
    std::shared_ptr<const PointMapping> model = io::read_model(files.model);
    const io::LoadedDataset d = io::load_dataset(files.dataset);
    const std::string name = d.manifest.display_name();
    server::ViewerSession session(std::move(model), name, server::viewer_map(d.plan_grid),
                                  server::viewer_map(d.gridmap));
    if (!files.pairs.empty())
      session.set_base_pairs(io::read_pairs_csv(files.pairs));
    server::ServerOptions options;
    options.host = args->host;
    options.port = args->port;
    if (fs::is_directory(args->web)) {
      options.web_root = args->web;
    } else {
      fmt::print(stderr, "note: no page at {} (--web): serving the API only\n", args->web);
    }
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
    fmt::print("serving   {} with model {} at http://{}:{}/ (Ctrl-C stops)\n", name,
               session.model()->name(), args->host, port);
    std::fflush(stdout);
    viewer.listen();
  });
}

}  // namespace floorgrid::app
