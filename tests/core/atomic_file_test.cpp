#include <gtest/gtest.h>
#include <radiosity/atomic_file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace fs = std::filesystem;
using namespace std::string_literals;

namespace {

// A fresh, empty directory per test so that "nothing left behind" means an empty listing.
class AtomicFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = fs::path(::testing::TempDir()) / (std::string("atomic_file_") + info->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::vector<std::string> listing() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(dir_)) names.push_back(entry.path().filename());
    return names;
  }
  static std::string contents(const fs::path& file) {
    std::ifstream in(file, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
  }

  fs::path dir_;
};

TEST_F(AtomicFileTest, TextLandsByteForByteAndNoTemporaryRemains) {
  const fs::path target = dir_ / "out.txt";
  const std::string text = "line one\r\nline two\n\0binary"s;
  rad::writeTextAtomically(target, text);
  EXPECT_EQ(contents(target), text);
  EXPECT_EQ(listing(), std::vector<std::string>{"out.txt"});
}

TEST_F(AtomicFileTest, BytesLand) {
  const fs::path target = dir_ / "out.bin";
  const std::vector<char> bytes = {'\0', '\xff', 'a', '\n'};
  rad::writeBytesAtomically(target, bytes);
  EXPECT_EQ(contents(target), std::string(bytes.begin(), bytes.end()));
  EXPECT_EQ(listing(), std::vector<std::string>{"out.bin"});
}

TEST_F(AtomicFileTest, WriterGetsATemporaryInTheTargetDirectory) {
  const fs::path target = dir_ / "image.exr";
  fs::path seen;
  rad::writeFileAtomically(target, [&](const fs::path& temporary) {
    seen = temporary;
    EXPECT_NE(temporary, target);
    EXPECT_FALSE(fs::exists(target)) << "the target must appear only after the rename";
    std::ofstream(temporary) << "done";
  });
  EXPECT_EQ(seen.parent_path(), target.parent_path());
  EXPECT_EQ(contents(target), "done");
  EXPECT_FALSE(fs::exists(seen));
}

TEST_F(AtomicFileTest, ExceptionInWriterLeavesNeitherTemporaryNorTarget) {
  const fs::path target = dir_ / "out.txt";
  EXPECT_THROW(rad::writeFileAtomically(target,
                                        [](const fs::path& temporary) {
                                          std::ofstream(temporary) << "partial";
                                          throw std::logic_error("writer failed");
                                        }),
               std::logic_error);
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFileTest, ExistingTargetIsReplacedOnlyOnSuccess) {
  const fs::path target = dir_ / "out.txt";
  rad::writeTextAtomically(target, "old");
  EXPECT_THROW(rad::writeFileAtomically(target,
                                        [](const fs::path& temporary) {
                                          std::ofstream(temporary) << "new but broken";
                                          throw std::runtime_error("disk full");
                                        }),
               std::runtime_error);
  EXPECT_EQ(contents(target), "old");
  rad::writeTextAtomically(target, "new");
  EXPECT_EQ(contents(target), "new");
  EXPECT_EQ(listing(), std::vector<std::string>{"out.txt"});
}

TEST_F(AtomicFileTest, MissingDirectoryThrowsRuntimeErrorNamingThePath) {
  const fs::path target = dir_ / "missing" / "out.txt";
  bool called = false;
  try {
    rad::writeFileAtomically(target, [&](const fs::path&) { called = true; });
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(target.string()), std::string::npos) << e.what();
  }
  EXPECT_FALSE(called);
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFileTest, WriterThatCreatesNothingIsAnError) {
  EXPECT_THROW(rad::writeFileAtomically(dir_ / "out.txt", [](const fs::path&) {}),
               std::runtime_error);
  EXPECT_TRUE(listing().empty());
}

TEST_F(AtomicFileTest, RepeatedWritesUseDistinctTemporaries) {
  const fs::path target = dir_ / "out.txt";
  fs::path first, second;
  rad::writeFileAtomically(target, [&](const fs::path& t) {
    first = t;
    std::ofstream(t) << 1;
  });
  rad::writeFileAtomically(target, [&](const fs::path& t) {
    second = t;
    std::ofstream(t) << 2;
  });
  EXPECT_NE(first, second);
  EXPECT_EQ(contents(target), "2");
}

}  // namespace

// A writer killed with kill -9 leaves its temporary behind; the next write into the directory
// removes those of dead processes (here: a child that has exited) and keeps a live writer's.
TEST_F(AtomicFileTest, TemporariesOfDeadWritersAreRemovedOnTheNextWrite) {
  const pid_t child = fork();
  if (child == 0) _exit(0);
  ASSERT_GT(child, 0);
  ASSERT_EQ(waitpid(child, nullptr, 0), child);
  const std::string dead = ".cache.bin.tmp-" + std::to_string(child) + "-3";
  const std::string live = ".cache.bin.tmp-" + std::to_string(getppid()) + "-0";
  for (const std::string& name : {dead, live, ".notes.tmp-x-1"s, "plain.txt"s})
    std::ofstream(dir_ / name) << "left over";
  rad::writeTextAtomically(dir_ / "out.txt", "new");
  std::vector<std::string> names = listing();
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{live, ".notes.tmp-x-1", "out.txt", "plain.txt"}));
}

// A device or a pipe given as the output (--stats /dev/stdout, a FIFO) is written to; replacing
// it by a regular file, as a rename would, broke /dev/null for every other program.
TEST_F(AtomicFileTest, AFifoIsWrittenToNotReplaced) {
  const fs::path fifo = dir_ / "pipe";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] { received = contents(fifo); });
  rad::writeTextAtomically(fifo, "through the pipe");
  reader.join();
  EXPECT_EQ(received, "through the pipe");
  EXPECT_TRUE(fs::is_fifo(fifo));
  EXPECT_EQ(listing(), std::vector<std::string>{"pipe"});
}

TEST_F(AtomicFileTest, ADirectoryTargetIsAnErrorNamingIt) {
  fs::create_directories(dir_ / "folder.png");
  try {
    rad::writeTextAtomically(dir_ / "folder.png", "x");
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("folder.png': it is a directory"), std::string::npos)
        << e.what();
  }
}
