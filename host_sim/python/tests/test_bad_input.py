"""Bad input raises a typed exception, in bounded time, never hangs: a port that is not
canalpath (an echo, a chatterer), a silent one, garbage frames, a vanished firmware."""
from __future__ import annotations

import time

import pytest
from peers import FakePeer

from canalpath import (Job, JobValueError, Link, LinkClosed, LinkError, LinkTimeout, NotCanalpath,
                       SilentPeer, StreamError)


@pytest.fixture
def peer(request):
    p = FakePeer(request.param)
    yield p
    p.close()


@pytest.mark.parametrize("peer", ["echo"], indirect=True)
def test_an_echoing_port_is_not_canalpath(peer):
    t0 = time.monotonic()
    with pytest.raises(NotCanalpath):
        Link.open(peer.path, timeout=1.0)
    assert time.monotonic() - t0 < 10


@pytest.mark.parametrize("peer", ["chatter"], indirect=True)
def test_another_device_is_not_canalpath(peer):
    with pytest.raises(NotCanalpath) as ei:
        Link.open(peer.path, timeout=1.0)
    assert "Hello from another device" in str(ei.value)


@pytest.mark.parametrize("peer", ["silent"], indirect=True)
def test_a_silent_port_raises_silent_peer(peer):
    t0 = time.monotonic()
    with pytest.raises(SilentPeer) as ei:
        Link.open(peer.path, timeout=1.0)
    assert isinstance(ei.value, LinkTimeout) and isinstance(ei.value, TimeoutError)
    assert time.monotonic() - t0 < 10
    assert b"\n" in peer.received and b"?" in peer.received   # it was asked, documented bytes only


@pytest.mark.parametrize("peer", ["garbage"], indirect=True)
def test_garbage_frames_raise_stream_error(peer):
    with Link.open(peer.path, timeout=1.0, run_timeout=2.0) as link:
        t0 = time.monotonic()
        with pytest.raises(StreamError) as ei:
            for _p in link.run(fmt="FRAMES"):
                pass
        assert "garbage" in str(ei.value) and time.monotonic() - t0 < 20
        assert link.last_run.bad_frames > 10 and link.last_run.points == 0
    # it was asked again (NAK) and told to stop (64 sync bytes and ABORT)
    assert bytes.fromhex("060083DFD77E") in bytes(peer.received)


def test_a_port_that_does_not_exist(tmp_path):
    with pytest.raises(LinkClosed):
        Link.open(str(tmp_path / "nothing"))


def test_firmware_gone_mid_run(fw):
    with Link.open(fw.link) as link:
        link.send_job(Job.from_file(__import__("conftest").JOBS.joinpath("paper_gcode.job").__str__()))
        n = 0
        with pytest.raises(LinkError):
            for _p in link.run():
                n += 1
                if n == 100:
                    fw.stop()
        assert n >= 100


def test_lines_the_firmware_would_refuse_are_not_sent(fw):
    with Link.open(fw.link) as link:
        with pytest.raises(JobValueError) as ei:
            link.command("CURVE LINE " + "1 " * 50)
        assert ei.value.code == 2 and ei.value.text == "line too long"
        with pytest.raises(JobValueError) as ei:
            link.command("SAFE \x01")
        assert ei.value.code == 8
        with pytest.raises(JobValueError) as ei:
            link.send_job(Job().feed(0.0009))
        assert ei.value.cause == "FEED 0.0009: 0 or 0.001..1e6"
        assert link.status().state == "Idle"
