#include "planner/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <algorithm>
#include <cstring>
#include <fstream>
#include <streambuf>
#include <vector>

namespace planner {

namespace {

[[noreturn]] void fail(const std::string& path, int err)
{
  throw OutputError("cannot write '" + path + "': " + (err ? std::strerror(err) : "write failed"));
}

// A stream buffer over a file descriptor that keeps the first errno: an ostream only
// knows "bad", and errno is long overwritten by the time a caller looks.
class FdBuf : public std::streambuf {
 public:
  explicit FdBuf(int fd) : fd_(fd), buf_(1 << 16) { setp(buf_.data(), buf_.data() + buf_.size()); }
  int error() const { return err_; }
  bool drain()
  {
    const char* p = pbase();
    while (p < pptr() && err_ == 0) {
      const ssize_t n = ::write(fd_, p, static_cast<size_t>(pptr() - p));
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) err_ = n < 0 ? errno : EIO;
      else p += n;
    }
    setp(buf_.data(), buf_.data() + buf_.size());
    return err_ == 0;
  }

 protected:
  int_type overflow(int_type ch) override
  {
    if (!drain()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }
  int sync() override { return drain() ? 0 : -1; }

 private:
  int fd_;
  int err_ = 0;
  std::vector<char> buf_;
};

}  // namespace

void write_file(const std::string& path, const std::function<void(std::ostream&)>& fill)
{
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) fail(path, errno);
  FdBuf buf(fd);
  std::ostream out(&buf);
  try {
    fill(out);
  } catch (...) {
    ::close(fd);
    throw;
  }
  out.flush();
  int err = buf.error();
  if (err == 0 && !out) err = EIO;
  if (::close(fd) != 0 && err == 0) err = errno;  // NFS and quota errors can surface only here
  if (err) fail(path, err);
}

void write_file(const std::string& path, const std::string& content)
{
  write_file(path, [&](std::ostream& o) { o << content; });
}

void check_xml_output(const std::string& path, const std::string& root)
{
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) fail(path, errno);
  if (S_ISREG(st.st_mode)) {
    std::ifstream in(path, std::ios::binary);
    const std::string tag = "</" + root + ">";
    const std::streamoff tail = std::min<std::streamoff>(st.st_size, static_cast<std::streamoff>(tag.size() + 64));
    std::string end(static_cast<size_t>(tail), '\0');
    in.seekg(st.st_size - tail);
    in.read(&end[0], tail);
    if (!in || end.find(tag) == std::string::npos)
      throw OutputError("cannot write '" + path + "': incomplete (no closing " + tag + "; full disk?)");
    return;
  }
  if (S_ISFIFO(st.st_mode) || S_ISSOCK(st.st_mode)) return;  // a reader owns it; a probe byte would reach it
  // A device: what SUMO wrote cannot be read back; a device that refuses one byte (/dev/full)
  // refused SUMO's output too.
  const int fd = ::open(path.c_str(), O_WRONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) fail(path, errno);
  const ssize_t n = ::write(fd, "\n", 1);
  const int err = n == 1 ? 0 : (n < 0 ? errno : EIO);
  ::close(fd);
  if (err) fail(path, err);
}

}  // namespace planner
