// Runs the `colmap` binary (Debian's COLMAP 3.8, CPU only) on a folder of photos, for `cinepath mesh
// --images DIR` without --colmap: feature extraction (one shared camera, OPENCV model, GPU off, one
// thread), exhaustive matching by cinepath (feature_matcher.h: brute force, border keypoints left out)
// written to raw_matches.txt, geometric verification by `colmap matches_importer --match_type raw`,
// mapping; `--random_seed 0` to each COLMAP step. COLMAP's own CPU matcher (FLANN) gives other matches
// every run, and its extractor other descriptor bytes for a few keypoints at the border: with these
// steps the same photos give the same model (byte-identical cameras.bin, images.bin, points3D.bin)
// every run, at any thread count. Flags as docs/dependencies.md gives them: with the GPU default and
// no display COLMAP aborts, so --SiftExtraction.use_gpu 0 / --SiftMatching.use_gpu 0.
//
// The workspace folder keeps database.db, raw_matches.txt, sparse/<n>/ and one log per COLMAP step
// (colmap_<step>.log); a workspace that already holds a sparse model is reused (delete it to start
// over). The largest model (most registered images) is returned.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace cinepath::photogrammetry {

struct ColmapRunOptions {
  std::string colmap_binary = "colmap";
  std::string camera_model = "OPENCV";
  bool single_camera = true;
  int num_threads = -1;  // matching, verification and mapping; -1: all cores (extraction runs on one)
};

// The extraction step alone: `colmap feature_extractor` into `database` (which must not exist yet), on
// one thread with the run's camera options, its log in `log`. RuntimeError when it fails.
void ExtractColmapFeatures(const std::filesystem::path& images_dir, const std::filesystem::path& database,
                           const ColmapRunOptions& options, const std::filesystem::path& log);

// Returns the sparse model folder. RuntimeError (with the log's last lines) when a step fails or no
// model comes out; InputError when the images folder does not exist. `on_step` (optional) is told the
// name of each step as it starts.
std::filesystem::path RunColmapReconstruction(const std::filesystem::path& images_dir,
                                              const std::filesystem::path& workspace, const ColmapRunOptions& options,
                                              const std::function<void(const std::string&)>& on_step = {});

}  // namespace cinepath::photogrammetry
