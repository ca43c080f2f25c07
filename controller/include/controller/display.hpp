#pragma once
// Display: can sumo-gui open an X display? Checked before sumo-gui starts, so that a
// missing display is one line ("cannot open display ...") instead of sumo-gui dying and
// TraCI retrying its connection for seconds before a "Broken pipe".
#include <string>

namespace controller {

// "" when $DISPLAY names an X server that accepts a connection (":N" -> the socket
// /tmp/.X11-unix/XN, "host:N" -> TCP port 6000+N), else why not.
std::string display_problem();

}  // namespace controller
