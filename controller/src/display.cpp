#include "controller/display.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>

namespace controller {
namespace {

bool connect_unix(const std::string& path, bool abstract)
{
  const int fd = ::socket(AF_UNIX, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_un a{};
  a.sun_family = AF_UNIX;
  const size_t off = abstract ? 1 : 0;  // Linux abstract socket: a leading NUL
  if (path.size() + off >= sizeof a.sun_path) {
    ::close(fd);
    return false;
  }
  std::memcpy(a.sun_path + off, path.data(), path.size());
  const socklen_t len = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + off + path.size());
  const bool ok = ::connect(fd, reinterpret_cast<sockaddr*>(&a), len) == 0;
  ::close(fd);
  return ok;
}

bool connect_tcp(const std::string& host, int port)
{
  addrinfo hints{}, *res = nullptr;
  hints.ai_socktype = SOCK_STREAM;
  if (::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &res) != 0) return false;
  bool ok = false;
  for (addrinfo* p = res; p && !ok; p = p->ai_next) {
    const int fd = ::socket(p->ai_family, p->ai_socktype, p->ai_protocol);
    if (fd < 0) continue;
    ok = ::connect(fd, p->ai_addr, p->ai_addrlen) == 0;
    ::close(fd);
  }
  ::freeaddrinfo(res);
  return ok;
}

}  // namespace

std::string display_problem()
{
  const char* env = std::getenv("DISPLAY");
  if (!env || !*env) return "cannot open display: DISPLAY is not set (no X server; try xvfb-run)";
  const std::string d = env;
  const size_t colon = d.rfind(':');
  if (colon == std::string::npos) return "cannot open display '" + d + "': not of the form [host]:N";
  const std::string host = d.substr(0, colon);
  const int n = std::atoi(d.c_str() + colon + 1);  // ":1.0" -> 1
  bool ok;
  if (host.empty() || host == "unix") {
    const std::string path = "/tmp/.X11-unix/X" + std::to_string(n);
    ok = connect_unix(path, false) || connect_unix(path, true);
  } else {
    ok = connect_tcp(host, 6000 + n);
  }
  return ok ? "" : "cannot open display '" + d + "': no X server answers there";
}

}  // namespace controller
