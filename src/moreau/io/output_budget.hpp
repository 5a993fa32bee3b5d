#pragma once
// The size of a run's output, projected once the first frame is written: `--duration 1e12`
// used to write frames without end. A run whose projection does not fit in the free space of its
// output directory's file system is refused before its first step (exit 2, the files it wrote
// removed); one that will write more than 1 GB says so, with its step count.
#include <filesystem>
#include <string>

namespace moreau {

/// The number of steps of `dt` in `duration` (at least 1); more than 1e15 is an InputError (a
/// run of that length cannot finish, and the count would overflow).
long run_step_count(double duration, double dt);

/// `steps` steps with output every `every` steps (and at the last), frame 0 already written to
/// `out_dir` (frames/, probes.csv, rigid_poses.csv).
/// `started`: when the run began; files in the directory older than that are not the run's and
/// are neither counted nor removed.
void check_output_budget(const std::string& out_dir, long steps, int every, std::filesystem::file_time_type started);

}  // namespace moreau
