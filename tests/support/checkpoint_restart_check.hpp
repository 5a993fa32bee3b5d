#pragma once
// The checkpoint test of every engine: a run of 2T and a run of T that writes a checkpoint,
// restored into a fresh World and run for T more, end in the same state (compared as the bytes
// of a checkpoint of each, which hold every field of the state) and the continued output
// directory holds the same probes.csv and frames as the uninterrupted run's.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "moreau/moreau.hpp"
#include "scene_test_helpers.hpp"

namespace moreau::test {

struct RestartCase {
  const char* name;
  const char* scene;  // a file in scenes/, or the scene's JSON
  std::vector<std::string> overrides;
  int steps;  // T in steps (a multiple of the scene's output.every)
};

inline std::string file_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline void expect_seamless_restart(const RestartCase& c) {
  namespace fs = std::filesystem;
  const std::string dir = temp_dir(std::string("restart-") + c.name), scene = scene_path(c.scene);

  World whole = World::load(scene, c.overrides);
  RunOptions options;
  options.out_dir = dir + "/whole";
  options.duration = 2 * c.steps * whole.dt();
  whole.run(options);

  World first = World::load(scene, c.overrides);
  options.out_dir = dir + "/parts";
  options.duration = c.steps * first.dt();
  options.checkpoint_every = c.steps;
  const RunResult r1 = first.run(options);
  ASSERT_EQ(r1.checkpoint, dir + "/parts/checkpoint.bin");
  ASSERT_TRUE(fs::exists(r1.checkpoint));

  World second = World::load(scene, c.overrides);
  second.restore(r1.checkpoint);
  EXPECT_EQ(second.time(), first.time());
  EXPECT_EQ(second.steps(), c.steps);
  options.checkpoint_every = 0;
  const RunResult r2 = second.run(options);
  EXPECT_EQ(r2.steps, c.steps);
  EXPECT_EQ(second.steps(), 2 * c.steps);

  // The whole state, bit for bit: a checkpoint of each world holds every field.
  whole.save_checkpoint(dir + "/whole.bin");
  second.save_checkpoint(dir + "/second.bin");
  const std::string a = file_bytes(dir + "/whole.bin"), b = file_bytes(dir + "/second.bin");
  ASSERT_GT(a.size(), 100u);
  EXPECT_TRUE(a == b) << c.name << ": the restarted run's state differs (" << a.size() << " and " << b.size() << " bytes)";
  EXPECT_EQ(whole.time(), second.time());

  // The continued output directory is the uninterrupted run's.
  EXPECT_EQ(file_bytes(dir + "/whole/probes.csv"), file_bytes(dir + "/parts/probes.csv"));
  std::vector<std::string> whole_frames, part_frames;
  for (const auto& f : fs::directory_iterator(dir + "/whole/frames")) whole_frames.push_back(f.path().filename().string());
  for (const auto& f : fs::directory_iterator(dir + "/parts/frames")) part_frames.push_back(f.path().filename().string());
  std::sort(whole_frames.begin(), whole_frames.end());
  std::sort(part_frames.begin(), part_frames.end());
  EXPECT_EQ(whole_frames, part_frames);
  ASSERT_FALSE(whole_frames.empty());
  EXPECT_EQ(file_bytes(dir + "/whole/frames/" + whole_frames.back()), file_bytes(dir + "/parts/frames/" + whole_frames.back()));
  for (const auto& f : fs::directory_iterator(dir + "/whole")) {
    if (f.path().extension() != ".pvd") continue;
    EXPECT_EQ(file_bytes(f.path().string()), file_bytes(dir + "/parts/" + f.path().filename().string()));
  }
}

}  // namespace moreau::test
