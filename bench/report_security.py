"""The DDS Security section of docs/benchmarks.md (hubrt_bench_security), for bench/report.py."""


def ms(value, digits=3):
    return f"{value:.{digits}f} ms"


def security_section(sections, security):
    """Appends the section to `sections` (a list of Markdown strings); nothing if it did not run."""
    if security is None:
        sections.append("## DDS Security on vs off\n\nNot measured: `hubrt_bench_security` did not run.\n")
        return
    rows = []
    for label, key in (("security off", "off"), ("security on", "on")):
        side = security[key]
        echo = side["echo_ms"]
        rows.append(f"| {label} | {echo['n']} | {ms(echo['p50'])} | {ms(echo['p90'])} | {ms(echo['p99'])} | "
                    f"{ms(echo['max'])} | {side['lost']} | {side['hub_cpu_percent']:.1f} % | "
                    f"{side['hub_rss_mb']:.1f} MB | {side['hub_threads']} |")
    off, on = security["off"], security["on"]
    lines = [
        "## DDS Security on vs off",
        "",
        f"`hubrt_bench_security`: payload {security['payload']}; security: {security['security']}. Two hubd "
        f"(Dock ECU, {security['hub_rate_hz']:g} Hz) in two private domains, one secured with a PKI made by "
        "`firmware/security` (as `hubctl security`), answer the same planner (C API, waitset; secured on the "
        f"secured side) in alternating blocks for {security['seconds']:.0f} s, a {security.get('gap_ms', 0):g} ms "
        "pause after each round trip (longer than the hubs' 10 ms budget of immediate States, so every echo is "
        "one). Hub CPU: user+system time over "
        "the measured blocks in % of one core; RSS: at the end.",
        "",
        "| | n | p50 | p90 | p99 | max | lost | hub CPU | hub RSS | hub threads |",
        "|---|---|---|---|---|---|---|---|---|---|",
        *rows,
        f"| on / off | | {security['ratio_p50']:.2f}x | | | | | "
        f"{on['hub_cpu_percent'] - off['hub_cpu_percent']:+.1f} pt | "
        f"{on['hub_rss_mb'] - off['hub_rss_mb']:+.1f} MB | |",
        "",
        "What security costs per command: the payload is encrypted and MACed (AES-GCM) by the writer and "
        "checked and decrypted by the reader on both legs; discovery and liveliness are encrypted too. The "
        "RSS difference is the three plugins, OpenSSL and the per-peer crypto state.",
    ]
    sections.append("\n".join(lines) + "\n")
