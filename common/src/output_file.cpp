// OutputFile: unique temporary beside the target (mkstemp), renamed into place on Commit;
// removed when abandoned or when the process is interrupted (SIGINT, SIGTERM, SIGHUP).
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <streambuf>
#include <system_error>

#include "stitchsim/common/files.h"

namespace stitchsim {
namespace {

namespace fs = std::filesystem;

// Temporaries alive now, for the signal handler (async-signal-safe: fixed arrays, unlink).
constexpr int kSlots = 32;
constexpr std::size_t kNameBytes = 4096;
char g_temp_names[kSlots][kNameBytes];
std::atomic<bool> g_temp_used[kSlots];

extern "C" void RemoveTemporariesAndReraise(int sig) {
  for (int i = 0; i < kSlots; ++i) {
    if (g_temp_used[i].load()) ::unlink(g_temp_names[i]);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

void InstallCleanupHandlersOnce() {
  static const bool installed = [] {
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
      struct sigaction sa {};
      sa.sa_handler = RemoveTemporariesAndReraise;
      sigemptyset(&sa.sa_mask);
      ::sigaction(sig, &sa, nullptr);
    }
    return true;
  }();
  (void)installed;
}

int RegisterTemporary(const std::string& name) {
  if (name.size() >= kNameBytes) return -1;  // still removed on failure, only not on a signal
  for (int i = 0; i < kSlots; ++i) {
    if (g_temp_used[i].load()) continue;
    std::memcpy(g_temp_names[i], name.c_str(), name.size() + 1);
    g_temp_used[i].store(true);
    return i;
  }
  return -1;
}

void UnregisterTemporary(int slot) {
  if (slot >= 0) g_temp_used[slot].store(false);
}

// A buffered stream onto a file descriptor; a failed write sets badbit on the stream.
class FdBuf final : public std::streambuf {
 public:
  void Attach(int fd) {
    fd_ = fd;
    setp(buf_, buf_ + sizeof(buf_));
  }

 protected:
  int_type overflow(int_type ch) override {
    if (!Drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return Drain() ? 0 : -1; }

 private:
  bool Drain() {
    const char* p = pbase();
    while (p < pptr()) {
      const ssize_t n = ::write(fd_, p, static_cast<std::size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return false;
      p += n;
    }
    setp(buf_, buf_ + sizeof(buf_));
    return true;
  }
  int fd_ = -1;
  char buf_[1 << 16];
};

std::string KindText(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISBLK(mode)) return "a block device";
  return "not a regular file";
}

}  // namespace

struct OutputFile::Impl {
  fs::path final_path;  // renamed onto on Commit
  fs::path temp_path;   // empty when writing through (FIFO, character device)
  int fd = -1;
  int slot = -1;
  FdBuf buf;
  std::ostream stream{&buf};

  void Discard() {
    if (fd >= 0) ::close(fd);
    fd = -1;
    if (!temp_path.empty()) ::unlink(temp_path.c_str());
    UnregisterTemporary(slot);
    slot = -1;
    temp_path.clear();
  }
};

std::unique_ptr<OutputFile> OutputFile::Open(const fs::path& target, std::string& error) {
  std::unique_ptr<OutputFile> out(new OutputFile);
  out->impl_ = std::make_unique<Impl>();
  Impl& im = *out->impl_;
  const std::string name = target.string();
  mode_t mode = 0666;
  bool keep_mode = false;
  bool through = false;
  im.final_path = target;
  struct stat lst {};
  if (::lstat(name.c_str(), &lst) == 0) {
    struct stat st = lst;
    if (S_ISLNK(lst.st_mode) && ::stat(name.c_str(), &st) != 0) {
      error = "cannot write " + name + ": it is a symbolic link to nothing";
      return nullptr;
    }
    if (S_ISFIFO(st.st_mode) || S_ISCHR(st.st_mode)) {
      through = true;
    } else if (S_ISREG(st.st_mode)) {
      std::error_code ec;
      if (S_ISLNK(lst.st_mode)) im.final_path = fs::canonical(target, ec);
      if (ec) {
        error = "cannot resolve " + name + ": " + ec.message();
        return nullptr;
      }
      mode = st.st_mode & 07777;
      keep_mode = true;
    } else {
      error = "cannot write " + name + ": it is " + KindText(st.st_mode) +
              " (outputs must be regular files, FIFOs or character devices)";
      return nullptr;
    }
  } else if (errno != ENOENT) {
    error = "cannot write " + name + ": " + std::strerror(errno);
    return nullptr;
  } else if (target.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(target.parent_path(), ec);  // a failure shows up below
  }
  if (through) {
    // O_NONBLOCK: a FIFO with no reader fails (ENXIO) instead of blocking; a reader gets
    // kFifoWaitTries x 10 ms to appear, then it is an error, never a hang.
    constexpr int kFifoWaitTries = 1000;
    for (int tries = 0;; ++tries) {
      im.fd = ::open(name.c_str(), O_WRONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
      if (im.fd >= 0 || errno != ENXIO || tries == kFifoWaitTries) break;
      ::usleep(10000);
    }
    if (im.fd < 0) {
      error = "cannot write " + name + ": " + std::strerror(errno);
      return nullptr;
    }
    ::fcntl(im.fd, F_SETFL, ::fcntl(im.fd, F_GETFL) & ~O_NONBLOCK);
    im.buf.Attach(im.fd);
    return out;
  }
  const fs::path dir = im.final_path.has_parent_path() ? im.final_path.parent_path() : ".";
  std::string pattern = (dir / ("." + im.final_path.filename().string() + ".tmp.XXXXXX")).string();
  InstallCleanupHandlersOnce();
  im.fd = ::mkstemp(pattern.data());
  if (im.fd < 0) {
    error = "cannot write a temporary file in " + dir.string() + ": " + std::strerror(errno);
    return nullptr;
  }
  im.temp_path = pattern;
  im.slot = RegisterTemporary(pattern);
  if (!keep_mode) {
    const mode_t mask = ::umask(0);
    ::umask(mask);
    mode &= ~mask;
  }
  ::fchmod(im.fd, mode);
  im.buf.Attach(im.fd);
  return out;
}

OutputFile::~OutputFile() {
  if (impl_) impl_->Discard();
}

std::ostream& OutputFile::Stream() { return impl_->stream; }

std::string OutputFile::Commit() {
  Impl& im = *impl_;
  const std::string shown = im.temp_path.empty() ? im.final_path.string() : im.temp_path.string();
  im.stream.flush();
  if (!im.stream || im.fd < 0) {
    im.Discard();
    return "write failed for " + shown;
  }
  const int rc = ::close(im.fd);
  im.fd = -1;
  if (rc != 0) {
    im.Discard();
    return "write failed for " + shown + ": " + std::strerror(errno);
  }
  if (im.temp_path.empty()) return {};
  if (::rename(im.temp_path.c_str(), im.final_path.c_str()) != 0) {
    const std::string why = std::strerror(errno);
    im.Discard();
    return "cannot rename " + shown + " to " + im.final_path.string() + ": " + why;
  }
  UnregisterTemporary(im.slot);
  im.slot = -1;
  im.temp_path.clear();
  return {};
}

}  // namespace stitchsim
