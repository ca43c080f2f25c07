"""python3 -m rtlacam [--version]: the version of the bindings."""
import sys

from . import __version__

if __name__ == "__main__":
    if sys.argv[1:] not in ([], ["--version"]):
        print("usage: python3 -m rtlacam [--version]", file=sys.stderr)
        sys.exit(2)
    print(f"rtlacam {__version__}")
