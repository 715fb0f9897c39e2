// writeFileAtomically (freeform/io/file.h; docs/mesh-io.md, "Errors"), the one writer behind every
// output of the library and the command-line tool: the target is either the old file or the whole
// new one, never half of it, and nothing else appears beside it, even when the writing process is
// killed with SIGKILL half-way (issue 16: a killed run used to leave its temporary file behind).
// The folder is compared entry by entry and byte by byte with what it held before, read with
// plain ifstream / directory_iterator, not through the writer.

#include <catch2/catch.hpp>

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include "freeform/core/error.h"
#include "freeform/io/file.h"

namespace test_file_write {

namespace fs = std::filesystem;
using freeform::Error;
using freeform::detail::TemporaryFile;
using Catch::Matchers::Contains;

namespace {

std::string readBytes(const fs::path& p)
{
    std::ifstream in(p, std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Every entry of the folder (hidden ones too), name -> contents ("<dir>" for a folder).
std::map<std::string, std::string> snapshot(const fs::path& dir)
{
    std::map<std::string, std::string> m;
    for (const auto& e : fs::directory_iterator(dir))
        m[e.path().filename().string()] = e.is_directory() ? std::string("<dir>") : readBytes(e.path());
    return m;
}

fs::path freshDir(const std::string& name)
{
    const fs::path dir = fs::path(FREEFORM_TEST_TMP) / "file_write" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void put(const fs::path& p, const std::string& bytes)
{
    std::ofstream out(p, std::ios::binary);
    out << bytes;
}

// 3 MB that are not all alike (every byte value, NUL included), to compare byte for byte.
std::string pattern(std::size_t n)
{
    std::string s(n, '\0');
    unsigned x = 12345;
    for (auto& c : s) {
        x = x * 1103515245u + 12345u;
        c = static_cast<char>(x >> 16);
    }
    return s;
}

// Does this folder's file system give unnamed files (O_TMPFILE)? Asked of the kernel directly.
bool unnamedFilesWork(const fs::path& dir)
{
#ifdef O_TMPFILE
    const int fd = ::open(dir.c_str(), O_TMPFILE | O_WRONLY, 0600);
    if (fd < 0) return false;
    ::close(fd);
    return ::access("/proc/self/fd", X_OK) == 0;
#else
    (void)dir;
    return false;
#endif
}

// Forks a child that writes 16 MB to target through the writer, flushes them (they are in the
// file), tells the parent, and waits forever; the parent looks at the folder while the child is
// mid-write, kills it with SIGKILL and looks again. Returns the folder seen mid-write and after.
std::pair<std::map<std::string, std::string>, std::map<std::string, std::string>>
killMidWrite(const fs::path& dir, const fs::path& target, TemporaryFile kind)
{
    int ready[2];
    int hold[2];
    REQUIRE(::pipe(ready) == 0);
    REQUIRE(::pipe(hold) == 0);
    const pid_t pid = ::fork();
    REQUIRE(pid >= 0);
    if (pid == 0) {
        ::close(ready[0]);
        ::close(hold[1]);
        try {
            freeform::detail::writeFileAtomically(
                target.string(),
                [&](std::ostream& out) {
                    const std::string block(1 << 20, 'x');
                    for (int i = 0; i < 16; ++i) out.write(block.data(), static_cast<std::streamsize>(block.size()));
                    out.flush();
                    const char c = 'w';
                    if (::write(ready[1], &c, 1) != 1) ::_exit(5);
                    char d = 0;
                    while (::read(hold[0], &d, 1) != 0) {
                    } // the parent never writes: blocks until SIGKILL
                    ::_exit(4);
                },
                kind);
        } catch (...) {
        }
        ::_exit(3);
    }
    ::close(ready[1]);
    ::close(hold[0]);
    char c = 0;
    const ssize_t got = ::read(ready[0], &c, 1); // returns once the child has written its 16 MB
    auto during = snapshot(dir);
    ::kill(pid, SIGKILL);
    int status = 0;
    ::waitpid(pid, &status, 0);
    ::close(ready[0]);
    ::close(hold[1]);
    REQUIRE(got == 1);
    REQUIRE(WIFSIGNALED(status));
    REQUIRE(WTERMSIG(status) == SIGKILL);
    return {during, snapshot(dir)};
}

} // namespace

TEST_CASE("a writer killed with SIGKILL mid-write leaves the folder exactly as it was", "[io][file][hardening]")
{
    const fs::path dir = freshDir("killed");
    if (!unnamedFilesWork(dir)) {
        WARN("the file system of " << dir << " has no O_TMPFILE: the writer falls back to a named temporary file");
        return;
    }
    put(dir / "other.txt", "a neighbour\n");

    SECTION("over an existing target")
    {
        put(dir / "out.obj", "v 0 0 0\n");
        const auto before = snapshot(dir);
        const auto [during, after] = killMidWrite(dir, dir / "out.obj", TemporaryFile::Anonymous);
        CHECK(during == before); // 16 MB written, none of it visible
        CHECK(after == before);  // the old target as it was, no temporary file
        CHECK(readBytes(dir / "out.obj") == "v 0 0 0\n");
    }
    SECTION("with no target yet")
    {
        const auto before = snapshot(dir);
        const auto [during, after] = killMidWrite(dir, dir / "new.ply", TemporaryFile::Anonymous);
        CHECK(during == before);
        CHECK(after == before);
        CHECK_FALSE(fs::exists(dir / "new.ply"));
    }
}

TEST_CASE("the named fallback keeps its temporary file visible while it writes", "[io][file]")
{
    // The limit docs/mesh-io.md states for file systems without O_TMPFILE: a kill mid-write leaves
    // the temporary file (never a half-written target).
    const fs::path dir = freshDir("killed_named");
    put(dir / "out.obj", "v 0 0 0\n");
    const auto before = snapshot(dir);
    const auto [during, after] = killMidWrite(dir, dir / "out.obj", TemporaryFile::Named);
    CHECK(during.size() == 2);
    CHECK(after.size() == 2);
    CHECK(after.at("out.obj") == "v 0 0 0\n");
    for (const auto& [name, bytes] : after)
        if (name != "out.obj") {
            CHECK(name.rfind(".out.obj.tmp", 0) == 0);
            CHECK(bytes.size() == std::size_t(16) << 20);
        }
}

TEST_CASE("atomic writes create and replace byte for byte and leave nothing else", "[io][file]")
{
    for (const TemporaryFile kind : {TemporaryFile::Anonymous, TemporaryFile::Named}) {
        INFO((kind == TemporaryFile::Anonymous ? "anonymous" : "named"));
        const fs::path dir = freshDir(kind == TemporaryFile::Anonymous ? "replace_anon" : "replace_named");
        const std::string big = pattern(3 << 20);
        const std::string path = (dir / "out.bin").string();

        // Created (no target yet), one byte at a time and in blocks larger than any buffer.
        freeform::detail::writeFileAtomically(
            path,
            [&](std::ostream& out) {
                for (std::size_t i = 0; i < 1000; ++i) out.put(big[i]);
                out.write(big.data() + 1000, static_cast<std::streamsize>(big.size() - 1000));
            },
            kind);
        CHECK(readBytes(path) == big);
        CHECK(snapshot(dir).size() == 1);

        // Replaced: the new bytes, nothing beside them.
        freeform::detail::writeFileAtomically(path, [](std::ostream& out) { out << "short\n"; }, kind);
        CHECK(readBytes(path) == "short\n");
        CHECK(snapshot(dir).size() == 1);

        // Empty output is an empty file, not a missing one.
        freeform::detail::writeFileAtomically(path, [](std::ostream&) {}, kind);
        CHECK(fs::exists(path));
        CHECK(fs::file_size(path) == 0);

        // A writer that fails keeps the old file and leaves nothing.
        put(path, "old");
        CHECK_THROWS_WITH(freeform::detail::writeFileAtomically(
                              path,
                              [&](std::ostream& out) {
                                  out << big;
                                  throw Error("disk on fire");
                              },
                              kind),
                          "disk on fire");
        CHECK(readBytes(path) == "old");
        CHECK(snapshot(dir).size() == 1);
    }
}

TEST_CASE("atomic writes give a new file the mode of an ordinary create", "[io][file]")
{
    const fs::path dir = freshDir("mode");
    const mode_t old = ::umask(027);
    for (const TemporaryFile kind : {TemporaryFile::Anonymous, TemporaryFile::Named}) {
        INFO((kind == TemporaryFile::Anonymous ? "anonymous" : "named"));
        const fs::path target = dir / (kind == TemporaryFile::Anonymous ? "a.txt" : "n.txt");
        freeform::detail::writeFileAtomically(target.string(), [](std::ostream& out) { out << "x"; }, kind);
        struct stat st {};
        REQUIRE(::stat(target.c_str(), &st) == 0);
        CHECK((st.st_mode & 07777) == 0640); // 0666 less the umask 027
        // An existing target of another mode is replaced by a file of that same mode (as before).
        REQUIRE(::chmod(target.c_str(), 0600) == 0);
        freeform::detail::writeFileAtomically(target.string(), [](std::ostream& out) { out << "y"; }, kind);
        REQUIRE(::stat(target.c_str(), &st) == 0);
        CHECK((st.st_mode & 07777) == 0640);
    }
    // The same as an ordinary create in this process.
    const fs::path plain = dir / "plain.txt";
    put(plain, "z");
    struct stat st {};
    REQUIRE(::stat(plain.c_str(), &st) == 0);
    CHECK((st.st_mode & 07777) == 0640);
    ::umask(old);
}

TEST_CASE("atomic writes name the path when they cannot write", "[io][file]")
{
    const fs::path dir = freshDir("errors");
    for (const TemporaryFile kind : {TemporaryFile::Anonymous, TemporaryFile::Named}) {
        INFO((kind == TemporaryFile::Anonymous ? "anonymous" : "named"));
        const std::string missing = (dir / "no_such_folder" / "out.obj").string();
        CHECK_THROWS_WITH(freeform::detail::writeFileAtomically(missing, [](std::ostream& out) { out << "x"; }, kind),
                          Contains(missing) && Contains("cannot open a temporary file"));
        // A folder in the target's place: refused, the folder kept, no temporary file beside it.
        fs::create_directories(dir / "taken");
        put(dir / "taken" / "inside.txt", "kept");
        const auto before = snapshot(dir);
        CHECK_THROWS_WITH(freeform::detail::writeFileAtomically((dir / "taken").string(), [](std::ostream& out) { out << "x"; }, kind),
                          Contains("taken") && Contains("cannot replace the file"));
        CHECK(snapshot(dir) == before);
        CHECK(readBytes(dir / "taken" / "inside.txt") == "kept");
    }
    // The plain entry points take the same route.
    const std::string plain = (dir / "plain.txt").string();
    freeform::writeFileAtomically(plain, "text");
    CHECK(readBytes(plain) == "text");
    freeform::writeFileAtomicallyWith(plain, [](std::ostream& out) { out << "stream"; });
    CHECK(readBytes(plain) == "stream");
}

} // namespace test_file_write
