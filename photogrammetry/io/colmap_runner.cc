#include "photogrammetry/io/colmap_runner.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <fstream>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "photogrammetry/io/colmap_database.h"
#include "photogrammetry/io/colmap_reader.h"
#include "photogrammetry/io/feature_matcher.h"

extern char** environ;

namespace cinepath::photogrammetry {
namespace {

namespace fs = std::filesystem;

std::string LogTail(const fs::path& log, int lines) {
  std::ifstream f(log);
  std::vector<std::string> all;
  std::string line;
  while (std::getline(f, line)) all.push_back(line);
  std::string out;
  for (size_t i = all.size() > static_cast<size_t>(lines) ? all.size() - lines : 0; i < all.size(); ++i) {
    out += "\n  " + all[i];
  }
  return out;
}

void RunStep(const std::string& step, std::vector<std::string> args, const fs::path& log) {
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  pid_t pid = 0;
  const int rc = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (rc != 0) {
    throw RuntimeError("colmap " + step + ": cannot run '" + args[0] + "' (is COLMAP installed? apt install colmap)");
  }
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw RuntimeError("colmap " + step + ": waitpid failed");
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    throw RuntimeError("colmap " + step + " failed (" +
                       (WIFEXITED(status) ? "exit " + std::to_string(WEXITSTATUS(status))
                                          : "signal " + std::to_string(WTERMSIG(status))) +
                       "); log " + log.string() + ":" + LogTail(log, 8));
  }
}

// The sparse model folder with the most registered images, or empty.
fs::path LargestModel(const fs::path& sparse) {
  fs::path best;
  size_t best_images = 0;
  if (!fs::is_directory(sparse)) return best;
  std::vector<fs::path> dirs;
  for (const auto& entry : fs::directory_iterator(sparse)) {
    if (entry.is_directory()) dirs.push_back(entry.path());
  }
  std::sort(dirs.begin(), dirs.end());
  for (const fs::path& d : dirs) {
    try {
      const size_t n = ReadColmapModel(d).images.size();
      if (n > best_images) best = d, best_images = n;
    } catch (const InputError&) {}
  }
  return best;
}

}  // namespace

void ExtractColmapFeatures(const fs::path& images_dir, const fs::path& database, const ColmapRunOptions& options,
                           const fs::path& log) {
  // One thread: with more, COLMAP numbers the images in the order they finish (other ids every run).
  RunStep("feature_extractor",
          {options.colmap_binary, "feature_extractor", "--database_path", database.string(), "--image_path",
           images_dir.string(), "--ImageReader.camera_model", options.camera_model, "--ImageReader.single_camera",
           options.single_camera ? "1" : "0", "--SiftExtraction.use_gpu", "0", "--SiftExtraction.num_threads", "1",
           "--random_seed", "0"},
          log);
}

fs::path RunColmapReconstruction(const fs::path& images_dir, const fs::path& workspace, const ColmapRunOptions& options,
                                 const std::function<void(const std::string&)>& on_step) {
  if (!fs::is_directory(images_dir)) throw InputError(Located(images_dir.string(), "not a directory (`images_dir`)"));
  fs::create_directories(workspace / "sparse");
  if (fs::path existing = LargestModel(workspace / "sparse"); !existing.empty()) return existing;
  const fs::path db = workspace / "database.db";
  fs::remove(db);
  const std::string threads = std::to_string(options.num_threads);
  auto step = [&](const std::string& name, std::vector<std::string> args) {
    if (on_step) on_step(name);
    RunStep(name, std::move(args), workspace / ("colmap_" + name + ".log"));
  };
  if (on_step) on_step("feature_extractor");
  ExtractColmapFeatures(images_dir, db, options, workspace / "colmap_feature_extractor.log");
  // Matching of our own (COLMAP's CPU matcher never repeats), verified by COLMAP (which repeats: the
  // same two-view geometries in 5 of 5 runs at all threads); border keypoints, whose descriptors
  // change from run to run, left out.
  if (on_step) on_step("feature_matcher");
  const fs::path match_list = workspace / "raw_matches.txt";
  std::vector<ColmapImageFeatures> features = ReadColmapFeatures(db);
  BlankBorderDescriptors(&features);
  FeatureMatchOptions match_options;
  match_options.num_threads = options.num_threads > 0 ? options.num_threads : 0;
  WriteColmapRawMatches(match_list, features, MatchAllPairs(features, match_options));
  step("matches_importer", {options.colmap_binary, "matches_importer", "--database_path", db.string(),
                            "--match_list_path", match_list.string(), "--match_type", "raw", "--SiftMatching.use_gpu",
                            "0", "--SiftMatching.num_threads", threads, "--random_seed", "0"});
  step("mapper",
       {options.colmap_binary, "mapper", "--database_path", db.string(), "--image_path", images_dir.string(),
        "--output_path", (workspace / "sparse").string(), "--Mapper.num_threads", threads, "--random_seed", "0"});
  const fs::path model = LargestModel(workspace / "sparse");
  if (model.empty()) {
    throw RuntimeError("colmap mapper registered no images (log " + (workspace / "colmap_mapper.log").string() + ":" +
                       LogTail(workspace / "colmap_mapper.log", 8) + ")");
  }
  return model;
}

}  // namespace cinepath::photogrammetry
