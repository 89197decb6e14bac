"""Helpers shared by the node benchmarks (scripts/bench_node.py, bench/node_soak.py).

Both launch launch/top_sim.launch without rviz against a private rosmaster and read the node's figures from
/proc; one copy keeps them measuring the same way. Import it after putting this file's directory on sys.path
(the scripts do that themselves, so they also work from catkin's devel-space relay).
"""
import math
import os
import signal
import socket
import subprocess
import sys
import time
import xmlrpc.client

REPO = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CLK_TCK = os.sysconf('SC_CLK_TCK')
CALLER = '/top_sim_bench'   # the caller id given to the master's and the node's XML-RPC APIs


def ros_environment(tool):
    """The environment with top_sim's devel space sourced (unless top_sim is already on the package path)."""
    env = dict(os.environ)
    env['PATH'] = '/usr/bin:' + env.get('PATH', '')
    env.setdefault('ROS_HOSTNAME', 'localhost')
    if subprocess.run(['rospack', 'find', 'top_sim'], env=env, capture_output=True).returncode == 0:
        return env
    ws = os.environ.get('TOP_SIM_WS', os.path.join(REPO, '.catkin_ws'))
    setup = os.path.join(ws, 'devel', 'setup.bash')
    if not os.path.isfile(setup):
        sys.exit(f'{tool}: top_sim is not on the ROS package path and {setup} does not exist: build first')
    out = subprocess.run(['bash', '-c', f'source "{setup}" && env -0'], env=env, capture_output=True, check=True).stdout
    return dict(kv.split('=', 1) for kv in out.decode().split('\0') if '=' in kv)


def free_port():
    """A TCP port nobody listens on now: the private master's, so that other masters are never touched."""
    with socket.socket() as s:
        s.bind(('localhost', 0))
        return s.getsockname()[1]


def cpu_ticks(pid):
    """utime + stime of a process (all its threads), in clock ticks."""
    with open(f'/proc/{pid}/stat') as f:
        fields = f.read().rsplit(')', 1)[1].split()
    return int(fields[11]) + int(fields[12])   # fields 14 and 15 of proc(5), counted after the comm field


def rss_kib(pid):
    """Resident set size of a process (VmRSS of /proc/<pid>/status) [KiB]."""
    with open(f'/proc/{pid}/status') as f:
        for line in f:
            if line.startswith('VmRSS:'):
                return int(line.split()[1])
    raise RuntimeError(f'/proc/{pid}/status has no VmRSS')


def loadavg_1min():
    """The 1-minute load average: the machine is shared, so every figure is read against it."""
    return os.getloadavg()[0]


def percentile(values, p):
    """Linear-interpolated percentile p in [0, 100] of a non-empty list."""
    v = sorted(values)
    k = (len(v) - 1) * p / 100.0
    lo, hi = math.floor(k), math.ceil(k)
    return v[lo] + (v[hi] - v[lo]) * (k - lo)


def node_pid(master_uri, node):
    """The pid of a node registered with the master (None while it is not registered)."""
    master = xmlrpc.client.ServerProxy(master_uri)
    code, _, uri = master.lookupNode(CALLER, node)
    if code != 1:
        return None
    code, _, pid = xmlrpc.client.ServerProxy(uri).getPid(CALLER)
    return pid if code == 1 else None


def start_master(env, tool, port=None):
    """Starts a private rosmaster (on a free port unless given), points env, os.environ and sys.path at it and
    waits until it answers. Returns the process; stop it with stop_group()."""
    port = port or free_port()
    env['ROS_MASTER_URI'] = f'http://localhost:{port}'
    os.environ.update(env)
    sys.path[:0] = [p for p in env.get('PYTHONPATH', '').split(':') if p and p not in sys.path]
    master = subprocess.Popen(['rosmaster', '--core', '-p', str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)
    deadline = time.time() + 30
    while True:
        try:
            xmlrpc.client.ServerProxy(env['ROS_MASTER_URI']).getSystemState(CALLER)
            return master
        except OSError:
            if time.time() > deadline or master.poll() is not None:
                stop_group(master)
                sys.exit(f'{tool}: rosmaster did not start on port {port}')
            time.sleep(0.2)


def launch_node(env, launch_args, node, log_path, timeout=60.0):
    """roslaunch top_sim top_sim.launch rviz:=false plus launch_args (a list of 'name:=value'), output to
    log_path. Returns (roslaunch process, node pid) once the node is registered; stop it with stop_group()."""
    log = open(log_path, 'w')
    launch = subprocess.Popen(['roslaunch', 'top_sim', 'top_sim.launch', 'rviz:=false'] + list(launch_args),
                              env=env, stdout=log, stderr=subprocess.STDOUT, start_new_session=True)
    log.close()   # the child has its own copy
    pid = None
    deadline = time.time() + timeout
    while pid is None and time.time() < deadline and launch.poll() is None:
        time.sleep(0.2)
        try:
            pid = node_pid(env['ROS_MASTER_URI'], node)
        except (OSError, xmlrpc.client.Error):
            pid = None
    if pid is None:
        stop_group(launch)
        raise RuntimeError(f'{node} did not come up within {timeout:g} s (see {log_path})')
    return launch, pid


def stop_group(proc, timeout=20.0):
    """SIGINT to the process group of a process started with start_new_session (roslaunch shuts its nodes down
    cleanly on SIGINT), SIGKILL if it is still there after timeout seconds."""
    try:
        os.killpg(proc.pid, signal.SIGINT)
    except ProcessLookupError:   # the whole group is gone already
        proc.wait()
        return
    try:
        proc.wait(timeout=timeout)
    except subprocess.TimeoutExpired:
        os.killpg(proc.pid, signal.SIGKILL)
        proc.wait()
