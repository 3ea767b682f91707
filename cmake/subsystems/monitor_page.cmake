# The monitor's page (docs/monitor.md): HTML, CSS and our own ES modules in share/monitor,
# served as they are (no build step). Installed as the package's share/plc_cell/monitor, where
# the server looks when the source tree it was built from is gone. dygraphs is not in the repository: the server serves Debian's
# libjs-dygraphs from /usr/share/javascript/dygraphs under /vendor/dygraphs/.
get_filename_component(PLC_CELL_MONITOR_PAGE ${PROJECT_SOURCE_DIR}/share/monitor REALPATH)
install(DIRECTORY ${PLC_CELL_MONITOR_PAGE}/ DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/monitor)

if(CATKIN_ENABLE_TESTING)
  include(${PROJECT_SOURCE_DIR}/cmake/pytest.cmake)
  # The page in headless chromium (chromium-driver, python3-selenium) against plc_node and the
  # plc_cell tool serving the demo cell, a cell switched to STOP, a recording, and a real PLC
  # (plc_cell monitor --fatek on a plc_cell run) that goes away and comes back; one monitor for
  # a line of cells (plc_cell run --line) and for the nodelets of one process.
  plc_cell_add_pytest(monitor_page FILES test/browser/test_monitor_page.py test/browser/test_monitor_stop.py
    test/browser/test_monitor_replay.py test/browser/test_monitor_remote.py test/browser/test_monitor_edit.py
    test/browser/test_monitor_line.py test/browser/test_monitor_nodelets.py
    DEPENDENCIES plc_node plc_cell_tool plc_cell_nodelets)
endif()
