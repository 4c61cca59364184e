"""Run an ET formation under ``perf`` with names for numba's compiled functions.

numba's machine code has no symbols ``perf`` can see. This script compiles the tick loop
in a fresh kernel directory (a kernel loaded from the disk cache keeps no function list),
writes ``/tmp/perf-<pid>.map`` (start, size and name of every function in the loop's
module; perf reads such a map for code it cannot place), prints its pid and then runs the
timed stretch, so that ``perf`` can be attached meanwhile:

    .venv/bin/python benchmarks/perf_map.py --shape disc1000 --start 3600 --seconds 900 &
    perf record -F 4000 -p <pid printed> -- sleep 5
    perf report --stdio --no-children --sort sym

Found this way: numba's reference counting (``NRT_incref``/``NRT_decref``) took 37 % of
a disc1000 run (see ``etswarm.sim.borrow``), and IDs compared as doubles in the
controller's table lookup.
"""

from __future__ import annotations

import gc
import os
import tempfile
import time
from pathlib import Path

import click
from bench_et import shape_path

from etswarm.algorithm.run import ETRun, RunConfig
from etswarm.sim.params import SimParams


def write_perf_map(dispatcher, path: Path) -> int:  # type: ignore[no-untyped-def]
    """Write a perf map of every function compiled into ``dispatcher``'s overloads (each
    entry's size runs to the next function); return how many were named."""
    found = []
    for cres in dispatcher.overloads.values():
        library = cres.library
        for fn in library._final_module.functions:
            if fn.is_declaration:
                continue
            address = library.get_pointer_to_function(fn.name)
            if address:
                found.append((address, fn.name))
    found.sort()
    with path.open("w") as out:
        for k, (address, name) in enumerate(found):
            size = found[k + 1][0] - address if k + 1 < len(found) else 0x10000
            out.write(f"{address:x} {size:x} {name}\n")
    return len(found)


@click.command()
@click.option("--shape", default="disc1000", show_default=True)
@click.option("--start", type=float, default=0.0, show_default=True,
              help="Simulated s run before the timed stretch.")
@click.option("--seconds", type=float, default=600.0, show_default=True)
@click.option("--threads", type=int, default=1, show_default=True)
@click.option("--control-threads", type=int, default=1, show_default=True,
              help="SimParams.control_threads (the split loop).")
@click.option("--message-delay", type=click.IntRange(0, 1), default=0, show_default=True,
              help="SimParams.message_delay_ticks (with --control-threads, the radio "
                   "runs beside the control).")
@click.option("--wait", type=float, default=2.0, show_default=True,
              help="Wall s to wait after printing the pid (to attach perf).")
def main(shape: str, start: float, seconds: float, threads: int, control_threads: int,
         message_delay: int, wait: float) -> None:
    """Write the perf map, print the pid, run ``seconds`` of the formation."""
    os.environ["ETSWARM_KERNEL_DIR"] = tempfile.mkdtemp(prefix="etswarm-perf-")
    run = ETRun(RunConfig(shape=shape_path(shape, Path(tempfile.mkdtemp())), seed=0,
                          max_time_s=1e9, layout="cluster"),
                sim_params=SimParams(threads=threads, control_threads=control_threads,
                                     message_delay_ticks=message_delay))
    run.advance(max(1, round(start * run.ticks_per_s)))
    named = write_perf_map(run.sim._kernel, Path(f"/tmp/perf-{os.getpid()}.map"))
    # Reading the compiled module's function list leaves some 10^6 Python objects behind,
    # and every full collection of the garbage collector then walked them all (a quarter
    # of the samples in a disc1000 profile): keep them out of the collector's sight.
    gc.collect()
    gc.freeze()
    print(f"pid {os.getpid()}: {named} functions named; attach perf now", flush=True)
    time.sleep(wait)
    cpu = time.process_time()
    run.advance(round(seconds * run.ticks_per_s))
    print(f"{seconds:.0f} simulated s in {time.process_time() - cpu:.2f} CPU s", flush=True)


if __name__ == "__main__":
    main()
