// io/atomic_file.hpp: a file is replaced whole or not at all, and no temporary file is left behind.
#include <doctest/doctest.h>

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "io/atomic_file.hpp"
#include "test_paths.hpp"

using namespace tessera;
namespace fs = std::filesystem;

namespace {

std::string read_text(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    return text.str();
}

// The files in `dir` other than those named, e.g. a temporary left behind.
int other_files(const fs::path& dir, std::initializer_list<const char*> names) {
    int count = 0;
    for (const auto& entry : fs::directory_iterator(dir)) {
        bool named = false;
        for (const char* name : names) named = named || entry.path().filename() == name;
        count += named ? 0 : 1;
    }
    return count;
}

std::string error_of(const std::function<void()>& write) {
    try {
        write();
    } catch (const io::WriteError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("atomic write: the text replaces the file whole, through a temporary name beside it") {
    const fs::path dir = test::output_dir("io_atomic_text");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path path = dir / "out.txt";
    io::write_text_atomically(path, "first");
    CHECK(read_text(path) == "first");
    fs::path seen;
    io::write_atomically(path, "file", [&](const fs::path& temporary) {
        seen = temporary;
        CHECK(read_text(path) == "first");  // the old file stays until the new one is whole
        std::ofstream(temporary) << "second";
        return std::string();
    });
    CHECK(seen.parent_path() == dir);  // the same folder: the rename is atomic
    CHECK(seen.filename().string().starts_with("out.txt.tmp."));
    CHECK(read_text(path) == "second");
    CHECK(io::temporary_path_for(path) != io::temporary_path_for(path));
    CHECK(other_files(dir, {"out.txt"}) == 0);
}

TEST_CASE("atomic write: a failed write keeps the old file, removes the temporary and names the file") {
    const fs::path dir = test::output_dir("io_atomic_failure");
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path path = dir / "image.png";
    io::write_text_atomically(path, "old");
    const auto fail_after_writing = [](const fs::path& temporary) {
        std::ofstream(temporary) << "half";
        return std::string("disk full");
    };
    CHECK(error_of([&] { io::write_atomically(path, "image", fail_after_writing); }) ==
          path.string() + ": cannot write image: disk full");
    CHECK(read_text(path) == "old");
    CHECK(other_files(dir, {"image.png"}) == 0);

    // A writer that throws: the temporary goes, the exception passes through.
    CHECK_THROWS_AS(io::write_atomically(path, "image",
                                         [](const fs::path& temporary) -> std::string {
                                             std::ofstream(temporary) << "half";
                                             throw std::logic_error("bug");
                                         }),
                    std::logic_error);
    CHECK(read_text(path) == "old");
    CHECK(other_files(dir, {"image.png"}) == 0);

    // The rename fails (a folder with a file in it holds the name): the temporary goes.
    fs::create_directories(dir / "taken");
    io::write_text_atomically(dir / "taken" / "inside", "x");
    const std::string moved = error_of([&] { io::write_text_atomically(dir / "taken", "new"); });
    CHECK_MESSAGE(moved.starts_with((dir / "taken").string() + ": cannot move the written file into place: "), moved);
    CHECK(other_files(dir, {"image.png", "taken"}) == 0);
}

TEST_CASE("atomic write: a missing folder is an error naming the file, unless the folders are created first") {
    const fs::path dir = test::output_dir("io_atomic_folders");
    fs::remove_all(dir);
    const fs::path path = dir / "a" / "b" / "out.json";
    const std::string missing = error_of([&] { io::write_text_atomically(path, "{}"); });
    CHECK_MESSAGE(missing.starts_with(path.string() + ": cannot write file: "), missing);
    io::create_parent_folders(path);
    io::write_text_atomically(path, "{}");
    CHECK(read_text(path) == "{}");
    io::write_text_atomically(dir / "blocker", "a file");
    const std::string blocked = error_of([&] { io::create_parent_folders(dir / "blocker" / "x" / "y.txt"); });
    CHECK_MESSAGE(blocked.starts_with((dir / "blocker" / "x").string() + ": cannot create folder: "), blocked);
}

TEST_CASE("atomic write: a copy of another file, and a missing source named") {
    const fs::path dir = test::output_dir("io_atomic_copy");
    fs::remove_all(dir);
    fs::create_directories(dir);
    io::write_text_atomically(dir / "from.txt", "golden");
    io::write_text_atomically(dir / "to.txt", "stale");
    io::copy_file_atomically(dir / "from.txt", dir / "to.txt");
    CHECK(read_text(dir / "to.txt") == "golden");
    const std::string missing = error_of([&] { io::copy_file_atomically(dir / "nowhere.txt", dir / "to.txt"); });
    CHECK_MESSAGE(missing.starts_with((dir / "to.txt").string() + ": cannot write a copy of " + (dir / "nowhere.txt").string()),
                  missing);
    CHECK(read_text(dir / "to.txt") == "golden");
    CHECK(other_files(dir, {"from.txt", "to.txt"}) == 0);
}
