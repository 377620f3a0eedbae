// Every write path (write_atomically / write_text_atomically — also used by the bench JSON —,
// save_scene_file, write_image) goes to a temporary file in the target folder and renames it into
// place. A failed write — unwritable folder, full disk, a writer that throws half-way — must
// report an error naming the path, leave any existing file byte-for-byte intact, and leave no
// temporary behind. As root, chmod does not stop writes, so the unwritable folder is a path below
// a regular file (ENOTDIR) or in /proc, and the full disk a 64 KiB tmpfs (mount works as root in
// this sandbox and in CI); without mount rights RLIMIT_FSIZE simulates the full disk instead.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/mount.h>
#include <sys/resource.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "core/io/atomic_file.h"
#include "core/io/image_file.h"
#include "core/io/scene_file.h"
#include "tests/reliability_support.h"

namespace pmsim {
namespace {

using reliability::read_file;
using reliability::ScratchDir;
namespace fs = std::filesystem;

std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// Runs `write`, which must throw std::runtime_error naming `path`.
void expect_write_error(const std::function<void()>& write, const std::string& path) {
  try {
    write();
    ADD_FAILURE() << "writing " << path << " did not fail";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
  } catch (...) {
    ADD_FAILURE() << "writing " << path << " threw something other than std::runtime_error";
  }
}

std::vector<float> gradient(int w, int h) {
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = float(i % 97) / 97.0f;  // incompressible-ish
  return rgb;
}

// All the write paths, each writing `path`.
std::vector<std::pair<std::string, std::function<void(const std::string&)>>> writers(size_t text_bytes,
                                                                                     int image_side) {
  return {
      {"text", [=](const std::string& p) { write_text_atomically(p, std::string(text_bytes, 'x')); }},
      {"scene", [](const std::string& p) { save_scene_file(Scene{}, p); }},
      {"png",
       [=](const std::string& p) {
         write_image(p, image_side, image_side, gradient(image_side, image_side), scene_to_json(Scene{}));
       }},
      {"exr",
       [=](const std::string& p) {
         write_image(p, image_side, image_side, gradient(image_side, image_side), scene_to_json(Scene{}));
       }},
      {"tif",
       [=](const std::string& p) {
         write_image(p, image_side, image_side, gradient(image_side, image_side), scene_to_json(Scene{}));
       }},
  };
}
std::string ext_for(const std::string& kind) { return kind == "text" || kind == "scene" ? "json" : kind; }

TEST(AtomicWrite, AWriterThatFailsHalfWayLeavesTheOldFileAndNoTemporary) {
  ScratchDir d;
  const std::string target = d.file("result.json", "old");
  expect_write_error(
      [&] {
        write_atomically(target, [](const std::string& tmp) {
          std::ofstream(tmp) << "half of the new con";
          throw std::runtime_error("simulated failure");
        });
      },
      target);
  EXPECT_EQ(read_file(target), "old");
  EXPECT_EQ(listing(d.path()), std::vector<std::string>{"result.json"});
}

TEST(AtomicWrite, SuccessfulWritesReplaceTheFileAndLeaveNoTemporary) {
  ScratchDir d;
  for (const auto& entry : writers(100, 4)) {  // (no structured bindings: clang 14 lambdas)
    const std::string& kind = entry.first;
    const auto& write = entry.second;
    SCOPED_TRACE(kind);
    const std::string target = d.file("out." + ext_for(kind), "old");
    write(target);
    EXPECT_TRUE(read_file(target) != "old");
    EXPECT_GT(fs::file_size(target), 3u);
    fs::remove(target);
    EXPECT_TRUE(listing(d.path()).empty()) << listing(d.path()).front();
  }
}

TEST(AtomicWrite, AnUnwritableFolderFailsNamingThePathAndChangesNothing) {
  ScratchDir d;
  const std::string blocker = d.file("not_a_folder", "a regular file");
  for (const auto& entry : writers(100, 4)) {  // (no structured bindings: clang 14 lambdas)
    const std::string& kind = entry.first;
    const auto& write = entry.second;
    SCOPED_TRACE(kind);
    const std::string target = blocker + "/out." + ext_for(kind);
    expect_write_error([&] { write(target); }, target);
    EXPECT_EQ(read_file(blocker), "a regular file");
    EXPECT_EQ(listing(d.path()), std::vector<std::string>{"not_a_folder"});
    // /proc accepts no new files, not even from root.
    const std::string proc = "/proc/pmsim_reliability_out." + ext_for(kind);
    expect_write_error([&] { write(proc); }, proc);
    EXPECT_FALSE(fs::exists(proc));
  }
  // An existing target that is a folder cannot be replaced by a file.
  fs::create_directory(d / "folder.json");
  expect_write_error([&] { write_text_atomically(d / "folder.json", "{}"); }, d / "folder.json");
  EXPECT_TRUE(fs::is_directory(d / "folder.json"));
  expect_write_error([&] { write_text_atomically("", "{}"); }, "");
}

// A folder whose file system is full: a 64 KiB tmpfs filled up by a filler file, or — when
// mounting is not allowed — RLIMIT_FSIZE set below any file's size (writes fail with EFBIG as
// they would with ENOSPC).
class FullDisk : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = scratch_.path() / "tiny";
    fs::create_directories(dir_);
    mounted_ = ::mount("tmpfs", dir_.c_str(), "tmpfs", 0, "size=64k") == 0;
    ::getrlimit(RLIMIT_FSIZE, &saved_);
  }
  void TearDown() override {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    if (mounted_) ::umount(dir_.c_str());
  }
  // Fills the disk (or lowers the file-size limit) once the user's old file exists.
  void fill() {
    if (mounted_) {
      std::ofstream f(dir_ / "filler", std::ios::binary);
      const std::string block(512, 'f');
      for (int i = 0; i < 1024 && f; ++i) f << block << std::flush;
    } else {
      ::signal(SIGXFSZ, SIG_IGN);
      rlimit tiny = saved_;
      tiny.rlim_cur = 8;
      ::setrlimit(RLIMIT_FSIZE, &tiny);
    }
  }
  void check_write_fails_cleanly(const std::string& kind);
  void unfill() {
    ::setrlimit(RLIMIT_FSIZE, &saved_);
    std::error_code ec;
    fs::remove(dir_ / "filler", ec);
  }
  ScratchDir scratch_;
  fs::path dir_;
  bool mounted_ = false;
  rlimit saved_{};
};

void FullDisk::check_write_fails_cleanly(const std::string& kind) {
  std::cerr << (mounted_ ? "full disk: 64 KiB tmpfs, filled\n" : "full disk: RLIMIT_FSIZE 8 bytes\n");
  const auto all = writers(4096, 64);
  const auto entry = std::find_if(all.begin(), all.end(), [&](const auto& e) { return e.first == kind; });
  ASSERT_NE(entry, all.end()) << "no writer of kind " << kind;
  const auto& write = entry->second;
  const std::string target = (dir_ / ("saved." + ext_for(kind))).string();
  { std::ofstream(target) << "the user's previous file"; }
  fill();
  expect_write_error([&] { write(target); }, target);
  unfill();
  EXPECT_TRUE(read_file(target) == "the user's previous file")
      << "the old file was replaced by " << fs::file_size(target) << " bytes";
  EXPECT_EQ(listing(dir_), std::vector<std::string>{"saved." + ext_for(kind)})
      << "a temporary was left behind";
}

TEST_F(FullDisk, ATextWriteFailsAndKeepsTheOldFile) { check_write_fails_cleanly("text"); }
TEST_F(FullDisk, ASceneSaveFailsAndKeepsTheOldFile) { check_write_fails_cleanly("scene"); }
TEST_F(FullDisk, AnExrWriteFailsAndKeepsTheOldFile) { check_write_fails_cleanly("exr"); }
TEST_F(FullDisk, ATiffWriteFailsAndKeepsTheOldFile) { check_write_fails_cleanly("tif"); }
// OpenImageIO's PNG writer reported success on a full disk, so write_image renamed a truncated
// temporary over the user's file. Finding F9 (docs/robustness.md).
TEST_F(FullDisk, APngWriteFailsAndKeepsTheOldFile) { check_write_fails_cleanly("png"); }

TEST_F(FullDisk, WritesSucceedAgainOnceThereIsRoom) {
  // The failure above is the disk's, not the path's: with room again the same writes succeed.
  fill();
  unfill();
  for (const auto& entry : writers(4096, 64)) {
    const std::string& kind = entry.first;
    const auto& write = entry.second;
    SCOPED_TRACE(kind);
    const std::string target = (dir_ / ("saved." + ext_for(kind))).string();
    EXPECT_NO_THROW(write(target));
    EXPECT_GT(fs::file_size(target), 100u);
  }
}

TEST(AtomicWrite, ConcurrentWritersOfOneFileLeaveOneWholeVersion) {
  // Two UI actions (autosave and a user save) may race; the reader must see one whole file.
  ScratchDir d;
  const std::string target = d / "scene.json";
  std::vector<std::thread> threads;
  for (int t = 0; t < 8; ++t)
    threads.emplace_back([&, t] {
      for (int i = 0; i < 50; ++i) write_text_atomically(target, std::string(1000 + t, char('a' + t)));
    });
  for (auto& th : threads) th.join();
  const std::string s = read_file(target);
  ASSERT_GE(s.size(), 1000u);
  EXPECT_EQ(s, std::string(s.size(), s[0]));
  EXPECT_EQ(s.size(), 1000u + size_t(s[0] - 'a'));
  EXPECT_EQ(listing(d.path()), std::vector<std::string>{"scene.json"});
}

}  // namespace
}  // namespace pmsim
