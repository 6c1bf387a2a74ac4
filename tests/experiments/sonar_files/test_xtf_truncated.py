"""A recording cut short (logging stopped, a full disk): the real Scotsman file cut at many
offsets either reads exactly the complete pings before the cut, with a one-line warning (file,
byte offset of the incomplete packet, bytes missing, pings read), or is refused in one line.
Reference: ``pyxtf.xtf_read`` of the whole file (an independent reader), keeping the pings whose
packets end before the cut (packet ends from the pings' own ``NumBytesThisRecord``)."""

from __future__ import annotations

import re

import numpy as np
import pytest

from sss_locus.experiments.sonar_files import observations as ob
from sss_locus.experiments.sonar_files import observations_xtf as ox
from sss_locus.experiments.sonar_files import xtf_packets as xp
from sss_locus.paths import DATA_DIR

REAL = DATA_DIR / "examples" / "your_pings" / "real" / "scotsman-iver2.xtf"
HEADER = 1024
CHAN1_SAMPLES = 256 + 64 + 2 * 1024 + 42  # NumSamples of channel 1 in a packet (XTF.H: byte 42 of a channel header)


@pytest.fixture(scope="module")
def whole():
    """The whole file's bytes, and pyxtf's pings with the byte where each packet starts and ends."""
    import pyxtf

    _, packets = pyxtf.xtf_read(str(REAL))
    pings = packets[pyxtf.XTFHeaderType.sonar]
    ends = HEADER + np.cumsum([int(p.NumBytesThisRecord) for p in pings])  # the file has sonar packets only
    starts = np.concatenate([[HEADER], ends[:-1]])
    data = REAL.read_bytes()
    assert ends[-1] == len(data)
    return data, pings, starts, ends


def _cuts(starts, ends):
    """Cut offsets: in the file header, at its end, in the first packet, at packet boundaries, in
    packet starts (14 bytes), ping headers (256), channel headers (64) and samples, at the last byte."""
    out = {0, 1, 500, HEADER - 1, HEADER, HEADER + 7, HEADER + 300, int(ends[-1]) - 1}
    for k in (1, 2, 57, 230, 460):
        s = int(starts[k])
        out |= {s, s + 1, s + 2, s + 9, s + 13, s + 14, s + 100, s + 255, s + 256, s + 300, s + 320, s + 1000,
                s + 2400, s + 2419, int(ends[k]) - 1}
    return sorted(out)


def test_cut_recording_reads_the_complete_pings_before_the_cut_or_one_line(tmp_path, whole):
    data, ref, starts, ends = whole
    path = tmp_path / "cut.xtf"
    outcomes = {"read whole": 0, "read truncated": 0, "refused": 0}
    for cut in _cuts(starts, ends):
        path.write_bytes(data[:cut])
        keep = [p for p, e in zip(ref, ends) if e <= cut]
        boundary = cut == HEADER or cut in set(ends.tolist())
        if cut < HEADER or (not keep and not boundary):
            with pytest.raises(ob.ObservationError) as err:
                xp.read_pings(path)
            msg = str(err.value)
            assert "\n" not in msg and msg.startswith("cut.xtf") and f"byte {cut}" in msg, (cut, msg)
            outcomes["refused"] += 1
            continue
        header, got = xp.read_pings(path)
        assert list(got) == [int(p.PingNumber) for p in keep], cut
        for p, q in zip(keep, got.values()):  # identical values: every header byte and every sample
            assert bytes(p) == bytes(q)
            assert [bytes(c) for c in p.ping_chan_headers] == [bytes(c) for c in q.ping_chan_headers]
            assert all(np.array_equal(a, b) and a.dtype == b.dtype for a, b in zip(p.data, q.data))
        if boundary:
            assert header.truncation is None, cut
            outcomes["read whole"] += 1
            continue
        k = len(keep)  # the incomplete packet is the next one
        t = header.truncation
        assert (t.offset, t.missing_bytes, t.length_known, t.n_pings) == (
            int(starts[k]), int(ends[k]) - cut if cut - starts[k] >= 14 else 14 - int(cut - starts[k]),
            cut - starts[k] >= 14, k), cut
        msg = t.message()
        assert "\n" not in msg and msg.startswith("cut.xtf is truncated") and f"byte {starts[k]}" in msg
        assert f"{t.missing_bytes} bytes missing" in msg and f"the {k} complete pings" in msg
        outcomes["read truncated"] += 1
    assert min(outcomes.values()) >= 4, outcomes


@pytest.mark.parametrize("edit, message", [
    # the incomplete last packet's magic number is wrong: not a packet cut short
    (lambda d, s: d.__setitem__(slice(s[20], s[20] + 2), b"\x00\x00"), "cut.xtf byte {s20}: not an XTF packet (no 0xFACE)"),
    # ... its channel count disagrees with the file header
    (lambda d, s: d.__setitem__(slice(s[20] + 4, s[20] + 6), (5).to_bytes(2, "little")),
     "cut.xtf byte {s20}: ping 20 has NumChansToFollow 5"),
    # a packet in the middle claims to run past the end of the file: a corrupt length, the rest refused
    (lambda d, s: d.__setitem__(slice(s[5] + 10, s[5] + 14), (10 ** 8).to_bytes(4, "little")),
     "cut.xtf byte {s5}: ping 5's NumBytesThisRecord 100000000 runs past the end of the file, but its channels end "
     "at byte {s6} where another packet starts"),
    # ... or its channel runs past the packet's own length
    (lambda d, s: d.__setitem__(slice(s[20] + CHAN1_SAMPLES, s[20] + CHAN1_SAMPLES + 4), (5000).to_bytes(4, "little")),
     "cut.xtf byte {s20}: ping 20's channel 1 runs past the end of its packet"),
])
def test_what_is_not_a_clean_cut_is_still_refused(tmp_path, whole, edit, message):
    data, _, starts, _ = whole
    d = bytearray(data[:int(starts[20]) + 3000])  # cut inside ping 20's starboard samples
    edit(d, starts)
    (tmp_path / "cut.xtf").write_bytes(bytes(d))
    with pytest.raises(ob.ObservationError) as err:
        xp.read_pings(tmp_path / "cut.xtf")
    assert message.format(s5=starts[5], s6=starts[6], s20=starts[20]) in str(err.value)
    assert "\n" not in str(err.value)


def test_sightings_of_a_cut_file_are_those_of_the_whole_file_and_say_it(tmp_path, whole):
    """The pings before the cut give the sightings the whole file gives, the table and the
    observations' warnings name the cut, and a ping after it is refused saying the file is cut."""
    data, _, starts, _ = whole
    rows = "feature,platform,file,ping,channel,sample\nA,iver2,{f},242,0,130\nB,iver2,{f},281,1,138\n"
    (tmp_path / "whole.xtf").write_bytes(data)
    (tmp_path / "cut.xtf").write_bytes(data[:int(starts[300]) + 777])
    (tmp_path / "w.csv").write_text(rows.format(f="whole.xtf"))
    (tmp_path / "c.csv").write_text(rows.format(f="cut.xtf"))
    full, cut = ox.read_xtf_sightings(tmp_path / "w.csv"), ox.read_xtf_sightings(tmp_path / "c.csv")
    differ = [c for c in full.columns if not full[c].equals(cut[c])]
    assert sorted(differ) == ["sample_order_how", "source", "xtf_file"]  # the evidence counts the pings read; file names
    assert cut["sample_order_how"].str.startswith("detected").all()
    assert full.attrs["xtf_truncated"] == [] and ox.observation_warnings(tmp_path / "w.csv") == []
    note = f"cut.xtf is truncated: the packet at byte {starts[300]} is incomplete ({4480 - 777} bytes missing); " \
           "read the 300 complete pings before it"
    assert len(cut.attrs["xtf_truncated"]) == 1 and cut.attrs["xtf_truncated"][0].startswith(note)
    assert ox.observation_warnings(tmp_path / "c.csv") == cut.attrs["xtf_truncated"]
    (tmp_path / "c.csv").write_text(rows.format(f="cut.xtf") + "C,iver2,cut.xtf,352,0,690\n")
    with pytest.raises(ob.ObservationError, match=r"^c.csv line 4, column ping: ping 352 is not in cut.xtf \(its pings "
                                                  rf"run 0 to 299; {re.escape(note)}"):
        ox.read_xtf_sightings(tmp_path / "c.csv")


def test_xtf_command_warns_on_stderr(tmp_path, whole, capsys):
    from sss_locus.pipeline.cli.command import main

    data, _, starts, _ = whole
    (tmp_path / "cut.xtf").write_bytes(data[:int(starts[100]) + 20])
    assert main(["xtf", str(tmp_path / "cut.xtf")]) == 0
    out, err = capsys.readouterr()
    line = (f"sss-locus xtf: warning: cut.xtf is truncated: the packet at byte {starts[100]} is incomplete "
            f"({4480 - 20} bytes missing); read the 100 complete pings before it")
    assert err.startswith(line) and len(err.strip().splitlines()) == 1
    assert "100 sonar pings, PingNumber 0 to 99" in out
