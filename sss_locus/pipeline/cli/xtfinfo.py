"""``sss-locus xtf FILE``: a one-screen summary of an XTF file, for writing a matches file
(channels and their sides, sample order, range setting, samples, navigation units, ping
numbers, time span, layback; :func:`sss_locus.experiments.sonar_files.xtf_summary.summary`)."""

from __future__ import annotations


def _clock(seconds: float) -> str:
    h, rest = divmod(seconds, 3600.0)
    m, s = divmod(rest, 60.0)
    return f"{int(h):02d}:{int(m):02d}:{s:05.2f}"


def _span(pair, fmt="{:g}") -> str:
    return fmt.format(pair[0]) if pair[0] == pair[1] else f"{fmt.format(pair[0])} to {fmt.format(pair[1])}"


def summary_lines(path, sample_order: str = "detect") -> list[str]:
    """The summary as lines of text (a bad file raises the reader's one-line error)."""
    from sss_locus.experiments.sonar_files.xtf_summary import summary

    s = summary(path, sample_order)
    lines = [f"{s['file']}: sonar {s['sonar'] or '?'} (recorded by {s['recorder'] or '?'}), navigation in {s['nav_units']}",
             f"{s['n_pings']} sonar pings"]
    if not s["n_pings"]:
        return lines
    lines[-1] += (f", PingNumber {s['ping_first']} to {s['ping_last']}"
                  + (f" ({s['ping_gaps']} numbers missing)" if s["ping_gaps"] else "")
                  + f"; time {_clock(s['time_first_s'])} to {_clock(s['time_last_s'])} "
                  f"({s['time_last_s'] - s['time_first_s']:.1f} s)")
    if s["truncated"]:  # the caller prints it on stderr too
        lines.append(f"warning: {s['truncated']}")
    if s["altitude_zero"]:
        lines.append(f"{s['altitude_zero']} ping(s) with altitude 0 (SensorPrimaryAltitude): do not match those")
    lines.append("layback: " + (f"{_span(s['layback_m'], '{:.3g}')} m (from {', '.join(s['layback_from'])})"
                                if s["layback_from"] else "none recorded (Layback and CableOut 0)"))
    if s["layback_bad"]:
        lines[-1] += (f"; {s['layback_bad']} ping(s) with a Layback that is negative or not a number: "
                      "do not match those")
    lines.append("channel  side        samples    range (m)     sample order (which end is near)")
    for c in s["channels"]:
        order = c.get("order", "")
        how = c.get("order_how", c.get("order_error", "not a sidescan channel" if c["type"] not in (1, 2) else ""))
        lines.append(f"{c['channel']:>7}  {c['side']:<10}  {_span(c['n_samples']):<9}  {_span(c['range_m'], '{:.4g}'):<12}  "
                     f"{order or '?'}: {how}")
    lines.append("matches file: feature, platform, file, ping (PingNumber), channel (0-based, as above), sample "
                 "(as stored: the reader turns a far-first channel round)")
    return lines
