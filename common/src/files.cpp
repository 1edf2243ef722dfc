#include "stitchsim/common/files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <system_error>

#include "stitchsim/common/limits.h"

namespace stitchsim {
namespace {

namespace fs = std::filesystem;

// "a directory", "a FIFO", ... for a message.
std::string KindOf(mode_t mode) {
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

std::string ErrnoText() { return std::strerror(errno); }

// The path made absolute and normal, symlinks of its existing part resolved.
fs::path Resolved(const fs::path& p) {
  std::error_code ec;
  fs::path abs = fs::absolute(p, ec);
  if (ec) abs = p;
  fs::path r = fs::weakly_canonical(abs, ec);
  return ec ? abs.lexically_normal() : r;
}

}  // namespace

FileText ReadRegularFile(const fs::path& path, std::uint64_t max_bytes) {
  FileText out;
  const std::string name = path.string();
  // O_NONBLOCK: opening a FIFO must not wait for a writer; fstat then refuses it.
  const int fd = ::open(name.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC | O_NOCTTY);
  if (fd < 0) {
    out.problem = errno == ENOENT ? FileProblem::kMissing : FileProblem::kUnreadable;
    out.error = name + ": cannot open: " + ErrnoText();
    return out;
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    out.problem = FileProblem::kUnreadable;
    out.error = name + ": cannot stat: " + ErrnoText();
    return out;
  }
  if (!S_ISREG(st.st_mode)) {
    out.problem = FileProblem::kNotRegular;
    out.error = name + ": is " + KindOf(st.st_mode) + ", not a regular file";
    return out;
  }
  const auto too_big = [&] {
    out.text.clear();
    out.problem = FileProblem::kTooLarge;
    out.error = name + ": larger than the limit of " + std::to_string(max_bytes) +
                " bytes for this kind of file (docs/limits.md)";
  };
  if (static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    too_big();
    return out;
  }
  out.text.reserve(static_cast<std::size_t>(st.st_size));
  char buf[1 << 16];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof(buf));
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) {
      out.text.clear();
      out.problem = FileProblem::kUnreadable;
      out.error = name + ": read failed: " + ErrnoText();
      return out;
    }
    if (n == 0) break;
    out.text.append(buf, static_cast<std::size_t>(n));
    if (out.text.size() > max_bytes) {  // the file grew while being read
      too_big();
      return out;
    }
  }
  return out;
}

std::string CheckStreamInput(const fs::path& path) {
  struct stat st {};
  if (::stat(path.string().c_str(), &st) != 0) {
    return "cannot open programme " + path.string() + ": " + ErrnoText();
  }
  if (S_ISREG(st.st_mode) || S_ISFIFO(st.st_mode)) return {};
  return path.string() + ": is " + KindOf(st.st_mode) + ", not a programme file or pipe";
}

std::optional<std::string> ReadFile(const fs::path& path) {
  FileText f = ReadRegularFile(path, limits::kMaxModelFileBytes);
  if (!f.ok()) return std::nullopt;
  return std::move(f.text);
}

bool IsInsideFolder(const fs::path& path, const fs::path& root) {
  const fs::path p = Resolved(path);
  const fs::path r = Resolved(root);
  auto pi = p.begin();
  for (auto ri = r.begin(); ri != r.end(); ++ri, ++pi) {
    if (ri->empty()) continue;  // a trailing separator
    if (pi == p.end() || *pi != *ri) return false;
  }
  return true;
}

std::string CheckDistinctOutputs(const std::vector<std::pair<std::string, std::string>>& outputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    for (std::size_t j = i + 1; j < outputs.size(); ++j) {
      const auto& [flag_a, a] = outputs[i];
      const auto& [flag_b, b] = outputs[j];
      if (a.empty() || b.empty()) continue;
      std::error_code ec;
      const bool same = Resolved(a) == Resolved(b) || fs::equivalent(a, b, ec);
      if (same) {
        return flag_a + " and " + flag_b + " name the same file " + b +
               "; give each output its own file";
      }
    }
  }
  return {};
}

std::string WriteFileAtomically(const fs::path& path, std::string_view contents) {
  std::string error;
  auto out = OutputFile::Open(path, error);
  if (!out) return error;
  out->Stream().write(contents.data(), static_cast<std::streamsize>(contents.size()));
  return out->Commit();
}

std::string WriteFilesAtomically(const std::vector<std::pair<fs::path, std::string>>& files) {
  std::vector<std::unique_ptr<OutputFile>> outs;
  for (const auto& [path, contents] : files) {
    std::string error;
    outs.push_back(OutputFile::Open(path, error));
    if (!outs.back()) return error;  // the ones opened so far remove their temporaries
    outs.back()->Stream().write(contents.data(), static_cast<std::streamsize>(contents.size()));
  }
  // Every file flushed before any is renamed: a full disk leaves all targets as they were.
  for (std::size_t i = 0; i < outs.size(); ++i) {
    if (!outs[i]->Stream().flush()) return "write failed for " + files[i].first.string();
  }
  for (auto& out : outs) {
    if (std::string err = out->Commit(); !err.empty()) return err;
  }
  return {};
}

fs::path DataDir() {
  if (const char* env = std::getenv("STITCHSIM_DATA_DIR"); env != nullptr && *env != '\0') {
    return env;
  }
  return STITCHSIM_DEFAULT_DATA_DIR;
}

fs::path ModelsDir() { return DataDir() / "models"; }

}  // namespace stitchsim
