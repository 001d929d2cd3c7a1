"""Federation settings: options and their variables, checks, exposure warnings, and how they
enter the router's Zenoh configuration (with or without Zenoh's own configuration file)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from launchkit.ros.federation import RouterOptions, RouterOptionsError
from launchkit.ros.session import router_config

LOOP = "tcp/127.0.0.1:7447"


def _tls_folder(path: Path) -> str:
    path.mkdir()
    for name in ("ca.pem", "cert.pem", "key.pem"):
        (path / name).write_text("not checked before Zenoh reads it\n")
    return str(path)


def test_variables_stand_in_for_options_not_given(tmp_path: Path) -> None:
    env = {
        "LAUNCHKIT_ROUTER_LISTEN": "tls/0.0.0.0:7448, tcp/127.0.0.1:7450",
        "LAUNCHKIT_ROUTER_CONNECT": "tls/10.0.0.1:7448",
        "LAUNCHKIT_ROUTER_MTLS": _tls_folder(tmp_path / "certs"),
    }
    options = RouterOptions.from_sources(environ=env)
    assert options.listen == ("tls/0.0.0.0:7448", "tcp/127.0.0.1:7450")
    assert options.connect == ("tls/10.0.0.1:7448",) and options.mtls
    given = RouterOptions.from_sources(connect=["tcp/10.0.0.2:7448"], environ=env)
    assert given.connect == ("tcp/10.0.0.2:7448",) and given.listen == options.listen


def test_bad_settings_are_user_errors(tmp_path: Path) -> None:
    folder = _tls_folder(tmp_path / "certs")
    with pytest.raises(RouterOptionsError, match="--tls and --mtls both given"):
        RouterOptions.from_sources(tls=folder, mtls=folder, environ={})
    with pytest.raises(RouterOptionsError, match="needs certificates"):
        RouterOptions.from_sources(listen=["tls/0.0.0.0:7448"], environ={})
    (tmp_path / "certs" / "key.pem").unlink()
    with pytest.raises(RouterOptionsError, match=r"missing key\.pem"):
        RouterOptions.from_sources(mtls=folder, environ={})
    with pytest.raises(RouterOptionsError, match="does not exist"):
        RouterOptions.from_sources(access=str(tmp_path / "nope.json5"), environ={})


def test_exposure_warnings(tmp_path: Path) -> None:
    folder = _tls_folder(tmp_path / "certs")
    assert RouterOptions().exposure_warnings(LOOP) == []
    plain = RouterOptions.from_sources(listen=["tcp/0.0.0.0:7448"], environ={})
    (warning,) = plain.exposure_warnings(LOOP)
    assert warning.startswith("listening on tcp/0.0.0.0:7448 without TLS: anyone who can reach")
    tls = RouterOptions.from_sources(listen=["tls/0.0.0.0:7448"], tls=folder, environ={})
    assert "server-only TLS" in tls.exposure_warnings(LOOP)[0]
    mtls = RouterOptions.from_sources(listen=["tls/0.0.0.0:7448"], mtls=folder, environ={})
    assert mtls.exposure_warnings(LOOP) == []
    assert "without TLS" in RouterOptions().exposure_warnings("tcp/192.168.1.2:7447")[0]


def test_options_enter_the_zenoh_configuration(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    access = tmp_path / "access.json5"
    access.write_text('{enabled: true, default_permission: "allow"}')
    options = RouterOptions.from_sources(
        listen=["tls/0.0.0.0:7448"],
        connect=["tls/10.0.0.1:7448"],
        mtls=_tls_folder(tmp_path / "certs"),
        access=str(access),
        environ={},
    )
    config = router_config(LOOP, options)
    assert json.loads(config.get_json("listen/endpoints")) == [LOOP, "tls/0.0.0.0:7448"]
    assert json.loads(config.get_json("connect/endpoints")) == ["tls/10.0.0.1:7448"]
    tls = json.loads(config.get_json("transport/link/tls"))
    assert tls["enable_mtls"] and tls["root_ca_certificate"].endswith("certs/ca.pem")
    assert json.loads(config.get_json("access_control"))["enabled"] is True
    # Zenoh's own file is used as is; the options add to its lists
    own = tmp_path / "router.json5"
    own.write_text('{mode: "router", listen: {endpoints: ["tcp/127.0.0.1:7999"]}}')
    monkeypatch.setenv("ZENOH_ROUTER_CONFIG_URI", str(own))
    config = router_config(LOOP, options)
    assert json.loads(config.get_json("listen/endpoints")) == [
        "tcp/127.0.0.1:7999",
        "tls/0.0.0.0:7448",
    ]
