"""Where the built plc_cell tool is, for test nodes that start it (rospack's search trips on
the workspace that lives inside the package, so the devel/install spaces are searched)."""
import os


def find_tool():
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        path = os.path.join(prefix, "lib", "plc_cell", "plc_cell")
        if prefix and os.access(path, os.X_OK):
            return path
    raise RuntimeError("plc_cell tool not found on CMAKE_PREFIX_PATH")
