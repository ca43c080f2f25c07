"""Where `cmake --install --prefix PREFIX` puts the rtlacam package (python/CMakeLists.txt).

Prints two lines: the folder, and "on-path" when this Python searches it (a site-packages
folder of its own under PREFIX: /usr/local/lib/python3.X/dist-packages on Debian, the user
site ~/.local/lib/python3.X/site-packages) or "off-path" (PREFIX/lib/python3.X/site-packages:
the caller then says to set PYTHONPATH).
"""
import os
import site
import sys
import sysconfig

prefix = os.path.realpath(sys.argv[1])
candidates = list(site.getsitepackages())
if site.ENABLE_USER_SITE is not False:
    candidates.append(site.getusersitepackages())
for d in candidates:
    if os.path.realpath(d).startswith(prefix + os.sep):
        print(d)
        print("on-path")
        sys.exit(0)
print(sysconfig.get_path("platlib", "posix_prefix", {"base": prefix, "platbase": prefix}))
print("off-path")
