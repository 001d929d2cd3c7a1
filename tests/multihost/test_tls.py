"""Federation beyond loopback is secured with the user's certificates: TLS, mutual TLS (a
router without a certificate from the right CA is refused) and Zenoh's access control."""

from __future__ import annotations

from pathlib import Path

from certs import Authority
from netns import Host, Hosts, Proc

NODES = Path(__file__).resolve().parent.parent / "ros" / "nodes"

ACCESS = """{
  enabled: true,
  default_permission: "allow",
  rules: [{id: "no_forbidden", messages: ["put"], flows: ["ingress"], permission: "deny",
           key_exprs: ["*/forbidden/**"]}],
  subjects: [{id: "host_b", cert_common_names: ["host-b"]}],
  policies: [{rules: ["no_forbidden"], subjects: ["host_b"]}],
}
"""


def router(host: Host, port: int, *args: str) -> Proc:
    proc = host.launchkit("router", "--router", f"tcp/127.0.0.1:{port}", *args)
    proc.expect(f"listening at tcp/127.0.0.1:{port}")
    return proc


def test_mutual_tls_admits_the_ca_s_hosts_and_refuses_others(hosts: Hosts, tmp_path: Path) -> None:
    ca = Authority("robot-ca")
    a_certs = ca.host_folder(tmp_path / "a", "host-a", hosts.a.address)
    b_certs = ca.host_folder(tmp_path / "b", "host-b", hosts.b.address)
    evil = Authority("someone-else").host_folder(tmp_path / "evil", "host-b", hosts.b.address)
    link = f"tls/{hosts.a.address}:7448"
    a = router(hosts.a, 7447, "--listen", link, "--mtls", str(a_certs))
    router(hosts.b, 7447, "--connect", link, "--mtls", str(b_certs)).expect(
        f"linked to the router at {link}"
    )
    stranger = router(hosts.b, 7449, "--connect", link, "--mtls", str(evil))

    hosts.a.start(str(NODES / "talker.py"))
    friend = hosts.b.start(str(NODES / "listener.py"))
    friend.expect("heard: hello")
    outsider = hosts.b.start(
        str(NODES / "listener.py"), env={"LAUNCHKIT_ROUTER": "tcp/127.0.0.1:7449"}
    )
    outsider.expect("listener ready")
    stranger.expect(f"no link to the router at {link} yet")
    assert outsider.rest() == [] and not [line for line in outsider.seen if "heard:" in line]
    assert not any("without TLS" in line or "server-only" in line for line in a.seen)


def test_server_only_tls_warns_that_anyone_may_connect(hosts: Hosts, tmp_path: Path) -> None:
    ca = Authority("robot-ca")
    link = f"tls/{hosts.a.address}:7448"
    a = router(
        hosts.a,
        7447,
        "--listen",
        link,
        "--tls",
        str(ca.host_folder(tmp_path / "a", "host-a", hosts.a.address)),
    )
    a.expect(f"listening on {link} with server-only TLS: the traffic is encrypted but any client")
    b = router(
        hosts.b,
        7447,
        "--connect",
        link,
        "--tls",
        str(ca.host_folder(tmp_path / "b", "host-b", hosts.b.address)),
    )
    b.expect(f"linked to the router at {link}")
    # a router that does not trust the server's CA does not link
    other = Authority("other").host_folder(tmp_path / "other", "host-b", hosts.b.address)
    router(hosts.b, 7449, "--connect", link, "--tls", str(other)).expect(
        f"no link to the router at {link} yet"
    )


def test_access_control_keeps_a_host_off_a_topic(hosts: Hosts, tmp_path: Path) -> None:
    ca = Authority("robot-ca")
    rules = tmp_path / "access.json5"
    rules.write_text(ACCESS)
    link = f"tls/{hosts.a.address}:7448"
    a_certs = ca.host_folder(tmp_path / "a", "host-a", hosts.a.address)
    b_certs = ca.host_folder(tmp_path / "b", "host-b", hosts.b.address)
    a = router(hosts.a, 7447, "--listen", link, "--mtls", str(a_certs), "--access", str(rules))
    a.expect(f"access control from {rules}")
    router(hosts.b, 7447, "--connect", link, "--mtls", str(b_certs)).expect(
        f"linked to the router at {link}"
    )
    forbidden = hosts.a.start(str(NODES / "listener.py"), "--ros-args", "-r", "chatter:=forbidden")
    allowed = hosts.a.start(str(NODES / "listener.py"), "--ros-args", "-r", "__node:=allowed")
    forbidden.expect("listener ready")
    hosts.b.start(str(NODES / "talker.py"))
    hosts.b.start(
        str(NODES / "talker.py"), "--ros-args", "-r", "__node:=t2", "-r", "chatter:=forbidden"
    )
    allowed.expect("heard: hello 50")  # a second of the talker on B
    assert forbidden.rest() == [] and not [line for line in forbidden.seen if "heard:" in line]
