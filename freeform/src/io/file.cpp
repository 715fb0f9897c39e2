#include "freeform/io/file.h"

#include <array>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <streambuf>
#include <system_error>

#if defined(__linux__)
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#endif

namespace freeform {

std::string readFile(const std::string& path)
{
    std::error_code ec;
    if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a directory, not a file");
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open the file for reading");
    std::ostringstream ss;
    ss << in.rdbuf();
    if (in.bad()) throw Error(path + ": reading failed");
    return ss.str();
}

void writeFileAtomically(const std::string& path, const std::string& text)
{
    writeFileAtomicallyWith(path, [&](std::ostream& out) { out.write(text.data(), static_cast<std::streamsize>(text.size())); });
}

namespace detail {

namespace {

namespace fs = std::filesystem;

fs::path folderOf(const fs::path& target)
{
    fs::path dir = target.parent_path();
    return dir.empty() ? fs::path(".") : dir;
}

// ".NAME.tmpRANDOM" beside the target: hidden, and in the same folder (so on the same file system)
// as the target, which rename needs.
fs::path temporaryName(const fs::path& target)
{
    static thread_local std::mt19937 random{std::random_device{}()};
    std::string name(1, '.');
    name += target.filename().string();
    name += ".tmp";
    name += std::to_string(random());
    return folderOf(target) / name;
}

// The fallback, and the only way off Linux: a named temporary file beside the target, renamed
// over it on success and removed on failure. A process killed before the rename leaves it behind.
void writeThroughNamedFile(const std::string& path, const std::function<void(std::ostream&)>& write)
{
    const fs::path target(path);
    const fs::path tmp = temporaryName(target);
    try {
        {
            std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
            if (!out) throw Error(path + ": cannot open a temporary file in " + folderOf(target).string() + " for writing");
            write(out);
            out.flush();
            if (!out) throw Error(path + ": writing failed");
        }
#if defined(__linux__)
        // Flush the bytes to the disk before they replace the old file (as the O_TMPFILE path does).
        const int fd = ::open(tmp.c_str(), O_RDONLY | O_CLOEXEC);
        if (fd < 0 || ::fsync(fd) != 0) {
            const int err = errno;
            if (fd >= 0) ::close(fd);
            throw Error(path + ": writing failed: " + std::strerror(err));
        }
        ::close(fd);
#endif
        std::error_code ec;
        fs::rename(tmp, target, ec);
        if (ec) throw Error(path + ": cannot replace the file: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        fs::remove(tmp, ignored);
        throw;
    }
}

#if defined(__linux__) && defined(O_TMPFILE)

// Closes the descriptor when the write ends, however it ends: an unnamed file that is closed
// without a name is gone.
struct FileDescriptor {
    int fd = -1;
    explicit FileDescriptor(int f) : fd(f) {}
    FileDescriptor(const FileDescriptor&) = delete;
    FileDescriptor& operator=(const FileDescriptor&) = delete;
    ~FileDescriptor()
    {
        if (fd >= 0) ::close(fd);
    }
};

bool writeAll(int fd, const char* data, std::size_t size)
{
    while (size > 0) {
        const ssize_t n = ::write(fd, data, size);
        if (n < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        data += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

// A buffered output stream over a file descriptor; a failed write sets badbit (the stream's
// ordinary failure) and keeps errno for the message.
class DescriptorBuffer : public std::streambuf {
public:
    explicit DescriptorBuffer(int fd) : fd_(fd) { setp(buffer_.data(), buffer_.data() + buffer_.size()); }
    int error = 0;

protected:
    int_type overflow(int_type c) override
    {
        if (!drain()) return traits_type::eof();
        if (!traits_type::eq_int_type(c, traits_type::eof())) {
            *pptr() = traits_type::to_char_type(c);
            pbump(1);
        }
        return traits_type::not_eof(c);
    }
    std::streamsize xsputn(const char* s, std::streamsize n) override
    {
        if (n >= static_cast<std::streamsize>(buffer_.size())) {
            // Large blocks go straight through, after what is buffered.
            if (!drain()) return 0;
            if (!writeAll(fd_, s, static_cast<std::size_t>(n))) {
                error = errno;
                return 0;
            }
            return n;
        }
        return std::streambuf::xsputn(s, n);
    }
    int sync() override { return drain() ? 0 : -1; }

private:
    bool drain()
    {
        const auto n = static_cast<std::size_t>(pptr() - pbase());
        if (n > 0 && !writeAll(fd_, pbase(), n)) {
            error = errno;
            return false;
        }
        setp(buffer_.data(), buffer_.data() + buffer_.size());
        return true;
    }

    int fd_;
    std::array<char, 1 << 16> buffer_{};
};

// Gives the unnamed file behind fd the name target: linked directly when target does not exist
// (nothing else ever appears in the folder), otherwise linked to a fresh temporary name and renamed
// over target, which replaces it atomically. Returns false, errno set, when the link itself is
// refused (no /proc, a file system without hard links): the caller falls back.
bool giveName(int fd, const std::string& path)
{
    const std::string proc = "/proc/self/fd/" + std::to_string(fd);
    if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, path.c_str(), AT_SYMLINK_FOLLOW) == 0) return true;
    if (errno != EEXIST) return false;
    const fs::path target(path);
    for (int attempt = 0;; ++attempt) {
        const fs::path tmp = temporaryName(target);
        if (::linkat(AT_FDCWD, proc.c_str(), AT_FDCWD, tmp.c_str(), AT_SYMLINK_FOLLOW) != 0) {
            if (errno == EEXIST && attempt < 16) continue;
            return false;
        }
        std::error_code ec;
        fs::rename(tmp, target, ec);
        if (ec) {
            std::error_code ignored;
            fs::remove(tmp, ignored);
            throw Error(path + ": cannot replace the file: " + ec.message());
        }
        return true;
    }
}

// Copies what the unnamed file holds into out (the fallback after a refused link).
void copyBack(int fd, std::ostream& out, const std::string& path)
{
    std::array<char, 1 << 16> block{};
    off_t at = 0;
    for (;;) {
        const ssize_t n = ::pread(fd, block.data(), block.size(), at);
        if (n < 0) {
            if (errno == EINTR) continue;
            throw Error(path + ": writing failed: " + std::strerror(errno));
        }
        if (n == 0) return;
        out.write(block.data(), n);
        at += n;
    }
}

#endif

} // namespace

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write, TemporaryFile kind)
{
#if defined(__linux__) && defined(O_TMPFILE)
    if (kind == TemporaryFile::Anonymous && ::access("/proc/self/fd", X_OK) == 0) {
        // The mode is that of an ordinary create: the kernel applies the umask to it.
        const FileDescriptor file(::open(folderOf(fs::path(path)).c_str(), O_TMPFILE | O_RDWR | O_CLOEXEC, 0666));
        // Refused (EOPNOTSUPP: the file system has no unnamed files; EISDIR or EINVAL: a kernel
        // before 3.11), or the folder cannot be written: the named path below says which.
        if (file.fd >= 0) {
            DescriptorBuffer buffer(file.fd);
            {
                std::ostream out(&buffer);
                write(out);
                out.flush();
                if (!out) {
                    const std::string reason = buffer.error != 0 ? std::string(": ") + std::strerror(buffer.error) : std::string();
                    throw Error(path + ": writing failed" + reason);
                }
            }
            if (::fsync(file.fd) != 0) throw Error(path + ": writing failed: " + std::strerror(errno));
            if (giveName(file.fd, path)) return;
            // The link was refused: the bytes are written, so copy them through the named path.
            writeThroughNamedFile(path, [&](std::ostream& out) { copyBack(file.fd, out, path); });
            return;
        }
    }
#else
    (void)kind;
#endif
    writeThroughNamedFile(path, write);
}

} // namespace detail

} // namespace freeform
