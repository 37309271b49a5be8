#include <doctest/doctest.h>

#include <fstream>
#include <string>

#include <sys/stat.h>
#include <unistd.h>

#include "io/input_file.hpp"
#include "test_paths.hpp"

namespace fs = std::filesystem;
using namespace tessera::io;

namespace {

fs::path write_file(const char* name, const std::string& text) {
    const fs::path path = tessera::test::output_dir("io") / name;
    std::ofstream(path, std::ios::binary) << text;
    return path;
}

std::string refusal(const fs::path& path, std::uint64_t limit = 1 << 20) {
    try {
        read_input_file(path, limit, "scene file");
    } catch (const InputFileError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST_CASE("io: a regular file is read whole, and its prefix alone") {
    const fs::path path = write_file("whole.txt", "hello, file");
    const std::vector<std::uint8_t> bytes = read_input_file(path, 100, "scene file");
    CHECK(std::string(bytes.begin(), bytes.end()) == "hello, file");
    CHECK(read_input_text(path, 11, "scene file") == "hello, file");
    CHECK(read_input_prefix(path, 5, "texture").size() == 5);
    CHECK(read_input_prefix(path, 500, "texture").size() == 11);
    CHECK(check_input_file(path, 11, "scene file") == 11);
}

TEST_CASE("io: a file over the caller's limit is refused before it is read, naming both sizes") {
    const fs::path path = write_file("large.txt", std::string(20000, 'x'));
    const std::string message = refusal(path, 10000);
    CHECK(message.find(path.string() + ": scene file of 19.5 KB is larger than the 10000 bytes it can need") == 0);
}

TEST_CASE("io: a sparse file of 8 GB is refused by its size, without reading it") {
    const fs::path path = tessera::test::output_dir("io") / "sparse.toml";
    { std::ofstream(path, std::ios::binary).put('x'); }
    REQUIRE(truncate(path.c_str(), 8ll << 30) == 0);
    const std::string message = refusal(path, 64 << 20);
    CHECK(message.find("scene file of 8.0 GB is larger than the 64.0 MB it can need") != std::string::npos);
    fs::remove(path);
}

TEST_CASE("io: FIFOs, devices and folders are refused by name before any read") {
    const fs::path fifo = tessera::test::output_dir("io") / "scene.fifo";
    fs::remove(fifo);
    REQUIRE(mkfifo(fifo.c_str(), 0600) == 0);
    // No writer ever opens the FIFO: a read would block forever.
    CHECK(refusal(fifo) == fifo.string() + ": cannot read scene file: it is a named pipe (FIFO), not a regular file");
    CHECK(refusal("/dev/zero") == "/dev/zero: cannot read scene file: it is a character device, not a regular file");
    CHECK(refusal("/dev/urandom").find("character device") != std::string::npos);
    CHECK(refusal(tessera::test::output_dir("io")).find("it is a folder, not a regular file") != std::string::npos);
    CHECK_THROWS_AS(check_input_file(fifo, 100, "texture"), InputFileError);
    CHECK_THROWS_AS(read_input_prefix("/dev/zero", 8, "texture"), InputFileError);
    fs::remove(fifo);
}

TEST_CASE("io: a missing file says so, and its reason is there without the path") {
    const fs::path path = tessera::test::output_dir("io") / "absent.toml";
    try {
        read_input_text(path, 100, "scene file");
        FAIL("no error");
    } catch (const InputFileError& e) {
        CHECK(e.reason() == "cannot open scene file: no such file");
        CHECK(std::string(e.what()) == path.string() + ": cannot open scene file: no such file");
    }
}

TEST_CASE("io: an output file may be absent or regular, not a FIFO or device") {
    const fs::path dir = tessera::test::output_dir("io");
    CHECK_NOTHROW(check_output_file(dir / "no_such.log", "the log"));
    CHECK_NOTHROW(check_output_file(write_file("present.log", "x"), "the log"));
    CHECK_THROWS_WITH_AS(check_output_file("/dev/null", "the log"),
                         "/dev/null: cannot write the log: it is a character device, not a regular file",
                         InputFileError);
}

TEST_CASE("io: byte counts read as people write them") {
    CHECK(byte_text(37) == "37 bytes");
    CHECK(byte_text(10240) == "10.0 KB");
    CHECK(byte_text(3ull << 30) == "3.0 GB");
    CHECK(byte_text(512ull << 20) == "512 MB");
}
