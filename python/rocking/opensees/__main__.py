"""python -m rocking.opensees SCENE.json [--compare]: runs a CLI scene in OpenSees with the
library deciding every opening and impact, and prints one JSON object
``{"events": [...], "summary": {...}}`` on standard output; ``--compare`` also runs the rigid
driver on the same scene and adds ``"compare"``: the events paired in order with their time
differences."""
import argparse
import json
import sys

import rocking

from . import compare_events, rigid_driver_events, run
from ._compare import find_cli


def main(argv=None):
    p = argparse.ArgumentParser(prog="python -m rocking.opensees", description=__doc__.split("\n\n")[0])
    p.add_argument("scene", help="a scene file (the CLI's schema)")
    p.add_argument("--compare", action="store_true", help="also run the rigid driver on the scene and compare the events")
    p.add_argument("--duration", type=float, help="stop earlier than the scene's duration (s)")
    p.add_argument("--max-events", type=int, help="stop after this many events")
    p.add_argument("--dt", type=float, help="OpenSees's time step (default min(scene dt, 1e-4))")
    p.add_argument("--block-stiffness", type=float, default=2e10,
                   help="Young's modulus of the blocks' beams (Pa, default 2e10); heavy, tall blocks need more "
                        "to stay stiff (docs/opensees.md §5)")
    p.add_argument("--cli", help="the rocking command line to run the rigid driver of --compare (default $ROCKING_CLI, "
                                 "else rocking on the PATH, else the package's own driver, rocking.simulate)")
    args = p.parse_args(argv)
    try:
        if args.compare:
            find_cli(args.cli)  # a --cli that does not exist, before the run rather than after
        return _run(args)
    except (rocking.RockingError, OSError, json.JSONDecodeError) as e:
        # A bad scene or path: the message names it; no traceback.
        p.exit(2, f"{p.prog}: error: {e}\n")


def _run(args):
    result = run(args.scene, dt=args.dt, duration=args.duration, max_events=args.max_events,
                 block_stiffness=args.block_stiffness)
    if args.compare:
        duration = result["summary"]["t_end"]
        rigid = rigid_driver_events(args.scene, duration=duration, cli=args.cli)
        result["compare"] = compare_events(result["events"], rigid)
    json.dump(result, sys.stdout, indent=1, default=float)
    sys.stdout.write("\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
