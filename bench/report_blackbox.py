"""The black box section of docs/benchmarks.md (hubrt_bench_blackbox), for bench/report.py."""


def blackbox_section(sections, blackbox):
    """Appends the section to `sections` (a list of Markdown strings); nothing measured if it did not run."""
    if blackbox is None:
        sections.append("## The black box on vs off\n\nNot measured: `hubrt_bench_blackbox` did not run.\n")
        return
    rows = []
    for rate in blackbox["rates"]:
        rows.append(
            f"| {rate['rate_hz']:g} Hz | {rate['cpu_off_pct']:.2f} % | {rate['cpu_on_pct']:.2f} % | "
            f"{rate['ratio_cpu']:.2f}x ({rate['ratio_cpu_min']:.2f}-{rate['ratio_cpu_max']:.2f}) | "
            f"{rate['same_program_change'] * 100:.0f} % | {rate['rss_off_mb']:.1f} MB | {rate['rss_on_mb']:.1f} MB | "
            f"{rate['rss_on_mb'] - rate['rss_off_mb']:+.1f} MB |")
    lines = [
        "## The black box on vs off",
        "",
        f"`hubrt_bench_blackbox`: {blackbox['hub']}; black box: {blackbox['black_box']}. Two hubd, one with its "
        "black box (every command taken and State published copied into its ring) and one run with "
        "`--no-black-box`, in one private domain, take the same planner's commands and are read by this "
        "process. CPU in turns (each hub measured while the other is stopped; the median of the rounds' "
        "on / off ratios, their range, and how far one program's own figure moved between its turns); RSS "
        "after the turns.",
        "",
        "| rate | CPU off | CPU on | on / off | turn-to-turn noise | RSS off | RSS on | RSS added |",
        "|---|---|---|---|---|---|---|---|",
        *rows,
        "",
        "What it costs: a memcpy of each State and command (a few hundred bytes) into the ring under a lock "
        "held for the copy only, no allocation (hubrt_hub_process_alloc_test runs with it on); the RSS is the "
        "ring, allocated and touched at start (blackbox.memory_kib; by default sized for 60 s of the hub's "
        "own rates, blackbox/ring_size.h: 8 MiB for every hub until 2026-11-29).",
    ]
    sections.append("\n".join(lines) + "\n")
