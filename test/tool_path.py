"""Where the built plc_cell tool is, for test nodes that start it (rospack's search trips on
the workspace that lives inside the package, so the devel/install spaces are searched)."""
import os


def find_tool(name="plc_cell"):
    """The tool, or another of the package's executables by name (plc_node, ...)."""
    for prefix in os.environ.get("CMAKE_PREFIX_PATH", "").split(os.pathsep):
        path = os.path.join(prefix, "lib", "plc_cell", name)
        if prefix and os.access(path, os.X_OK):
            return path
    raise RuntimeError("%s not found on CMAKE_PREFIX_PATH" % name)
