"""deploy/clusters/ssh-netns3.cluster: multi_host's cluster (4 zone ranks over h1 and h2, the
gateway and 32 players on h3) with every host reached by ssh, as on real machines. Each of the
three namespaces runs a real OpenSSH server with its own hostname, host key and a client key
made for this run; the launcher runs in a fourth namespace on the same bridge and reaches them
with [cluster] ssh_options only, so nothing in ~/.ssh or /etc/ssh is read or written. Same checks
as multi_host, and no sshd, process, namespace, link or key may be left, pass or fail. Needs root
(CAP_NET_ADMIN) and sshd (openssh-server, deploy/setup.sh)."""
import os
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import harness as h
import namespace_hosts as hosts

HOSTS = 3  # h1..h3 run sshd; h4 runs the launcher

SSHD_CONFIG = """# Written by tests/integration/multi_host_ssh.py: root by this run's key only.
ListenAddress {address}
HostKey {tmp}/host_key
PidFile {tmp}/sshd-h{i}.pid
AuthorizedKeysFile {tmp}/client_key.pub
PermitRootLogin prohibit-password
PasswordAuthentication no
KbdInteractiveAuthentication no
StrictModes no
UsePAM no
UseDNS no
PrintMotd no
PrintLastLog no
"""


def sshd_path():
    # sshd re-executes itself and wants its absolute path; /usr/sbin may not be on a test's PATH.
    path = shutil.which("sshd") or shutil.which("sshd", path="/usr/sbin:/usr/local/sbin:/sbin")
    if not path:
        h.fail("sshd not found: install openssh-server (deploy/setup.sh lists it)")
    return path


def keygen(path):
    subprocess.run(["ssh-keygen", "-q", "-t", "ed25519", "-N", "", "-f", path], check=True)


def ssh_home_state():
    home = Path.home() / ".ssh"
    return sorted(p.name for p in home.iterdir()) if home.is_dir() else None


def wait_for_sshd(launcher_ns, i, options, deadline):
    """ssh to hI from the launcher's namespace answers with hI's own hostname."""
    while True:
        r = subprocess.run(["ip", "netns", "exec", launcher_ns, "ssh", *options, "-o", "ConnectTimeout=5",
                            f"root@10.77.0.{i}", "hostname"], capture_output=True, text=True, timeout=30)
        if r.returncode == 0:
            h.check(r.stdout.strip() == f"h{i}", f"ssh root@10.77.0.{i} reaches host h{i} ({r.stdout.strip()})")
            return
        if time.monotonic() > deadline:
            h.fail(f"ssh root@10.77.0.{i} hostname: {r.stderr.strip() or 'exit ' + str(r.returncode)}")
        time.sleep(0.2)


ssh_home_before = ssh_home_state()
sshd = sshd_path()
# sshd's privilege-separation folder, which the package's service would make at boot.
privsep = Path("/run/sshd")
made_privsep = not privsep.exists()
tmp = tempfile.mkdtemp(prefix="zs_ssh_")
sshds = []
try:
    privsep.mkdir(mode=0o755, exist_ok=True)
    run, log = Path(tmp) / "run", Path(tmp) / "cluster.log"
    keygen(f"{tmp}/host_key")
    keygen(f"{tmp}/client_key")
    options = ["-F", "/dev/null", "-i", f"{tmp}/client_key", "-o", "IdentitiesOnly=yes",
               "-o", "UserKnownHostsFile=/dev/null", "-o", "GlobalKnownHostsFile=/dev/null",
               "-o", "StrictHostKeyChecking=no", "-o", "LogLevel=ERROR"]
    with hosts.namespaces(HOSTS + 1) as ns:
        for i in range(1, HOSTS + 1):
            config = Path(tmp) / f"sshd-h{i}.conf"
            config.write_text(SSHD_CONFIG.format(address=f"10.77.0.{i}", tmp=tmp, i=i))
            # Its own hostname, as the netns reach gives: Open MPI's daemons on one hostname collide.
            sshds.append(subprocess.Popen(
                ["ip", "netns", "exec", ns[i - 1], "unshare", "--uts", "sh", "-c", 'hostname "$0" && exec "$@"',
                 f"h{i}", sshd, "-D", "-e", "-f", config],
                stdout=open(Path(tmp) / f"sshd-h{i}.log", "w"), stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL))
        deadline = time.monotonic() + 30
        for i in range(1, HOSTS + 1):
            wait_for_sshd(ns[HOSTS], i, options, deadline)
        env = hosts.cluster_env()
        env["ZONESIM_SSH_OPTIONS"] = " ".join(options)
        h.run(["ip", "netns", "exec", ns[HOSTS], "bash", h.SOURCE_DIR / "deploy/cluster.sh",
               h.SOURCE_DIR / "deploy/clusters/ssh-netns3.cluster", run], log, env, timeout=150)
        hosts.check_run(run, log.read_text())
        for p in sshds:
            p.terminate()
        h.check(all(p.wait(timeout=10) is not None for p in sshds), f"{HOSTS} sshds stopped")
finally:
    # The namespaces' teardown has killed whatever ran in them, sshds included.
    for p in sshds:
        if p.poll() is None:
            p.kill()
            p.wait()
    shutil.rmtree(tmp, ignore_errors=True)
    if made_privsep:
        shutil.rmtree(privsep, ignore_errors=True)
h.check(not hosts.processes_under(tmp), f"no process left behind (sshd or cluster) {hosts.processes_under(tmp)}")
h.check(not Path(tmp).exists(), "keys, configurations and run folder removed")
h.check(ssh_home_state() == ssh_home_before, f"~/.ssh untouched ({ssh_home_before} before, {ssh_home_state()} after)")
print("multi-host over ssh passed")
