"""scripts/plot_oven.py reads a `plc_cell sim --trace` CSV and a bag of plc_node's
Temperature topic, and draws the same figure from either."""
import os
import subprocess
import tempfile

# realpath: run from the workspace, this file is reached through its links to the package.
ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.realpath(__file__))))
TOOL = os.path.join(ROOT, ".build", "ws", "devel", "lib", "plc_cell", "plc_cell")
PLOT = os.path.join(ROOT, "scripts", "plot_oven.py")


def run(*args):
    return subprocess.run(list(args), stdout=subprocess.PIPE, stderr=subprocess.STDOUT, check=True,
                          universal_newlines=True).stdout


def test_plots_a_sim_trace_of_the_oven():
    d = tempfile.mkdtemp()
    trace, png = os.path.join(d, "oven.csv"), os.path.join(d, "oven.png")
    run(TOOL, "sim", "--config", os.path.join(ROOT, "examples/oven/oven.yaml"), "--duration", "1800s",
        "--watch", "R0,R200", "--trace", trace)
    out = run("/usr/bin/python3", PLOT, trace, png)
    # The oven example reaches 200.0 degC from 25 degC and holds it (docs/analog-and-temperature.md).
    fields = out.split(",")
    final = float(fields[1].split()[1])
    peak = float(fields[2].split()[1])
    assert 199.0 <= final <= 201.0, out
    assert 200.0 <= peak <= 201.5, out
    assert "within 200 +- 1 from never" not in out, out
    assert os.path.getsize(png) > 10000
    with open(png, "rb") as f:
        assert f.read(8) == b"\x89PNG\r\n\x1a\n"


def test_plots_a_bag_of_the_temperature_topic():
    import rosbag
    import rospy
    from sensor_msgs.msg import Temperature
    d = tempfile.mkdtemp()
    bag_path, png = os.path.join(d, "oven.bag"), os.path.join(d, "oven.png")
    with rosbag.Bag(bag_path, "w") as bag:
        for k in range(300):  # 25 -> 200 degC exponential approach, 1 sample/s
            m = Temperature()
            m.header.stamp = rospy.Time(1000 + k)
            m.temperature = 200.0 - 175.0 * (0.98 ** k)
            bag.write("/plc_node/temperature/oven_temp", m, m.header.stamp)
    out = run("/usr/bin/python3", PLOT, bag_path, png)
    assert out.startswith("300 samples"), out
    final = 200.0 - 175.0 * (0.98 ** 299)
    assert "final %.1f degC" % final in out, out
    # 175 * 0.98^k <= 1 from k = 256 on.
    assert "from 256.0 s" in out, out
    assert os.path.getsize(png) > 10000


def test_refuses_a_csv_it_does_not_know():
    d = tempfile.mkdtemp()
    bad = os.path.join(d, "x.csv")
    with open(bad, "w") as f:
        f.write("a,b\n1,2\n")
    p = subprocess.run(["/usr/bin/python3", PLOT, bad, os.path.join(d, "x.png")], stdout=subprocess.PIPE,
                       stderr=subprocess.STDOUT, universal_newlines=True)
    assert p.returncode != 0
    assert "not a plc_cell sim --trace CSV" in p.stdout
