"""python -m ssgi: the programs render, reference and compare through the module, for a pip
install that has no programs. `python -m ssgi render --help` says each one's options. A scene is
a file or the name of a shipped scene (ssgi.scene_names()). Bad input: `error: ...`, exit 2."""
import argparse
import json
import os
import sys
from typing import Any, List, Optional, Tuple, Union

import ssgi


def _size(text: str) -> tuple:
    width, _, height = text.partition("x")
    try:
        return int(width), int(height)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}' is not WIDTHxHEIGHT") from None


def _setting(text: str) -> Tuple[str, Any]:
    name, equals, value = text.partition("=")
    if not equals:
        raise argparse.ArgumentTypeError(f"'{text}' is not NAME=VALUE")
    try:
        number = json.loads(value.lower() if value.lower() in ("true", "false") else value)
    except ValueError:
        raise argparse.ArgumentTypeError(f"'{text}': '{value}' is not a number") from None
    return name, number


def _scene(text: str, settings: List[Tuple[str, Any]]) -> ssgi.Scene:
    # A name without an extension that is no file names a shipped scene (else: the names).
    shipped = not os.path.exists(text) and not os.path.splitext(text)[1]
    path: Union[str, os.PathLike] = ssgi.scene_file(text) if shipped else text
    return ssgi.Scene(path, settings=dict(settings))


def main(argv: Optional[List[str]] = None) -> int:
    parser = argparse.ArgumentParser(prog="python -m ssgi", description=__doc__)
    programs = parser.add_subparsers(dest="program", required=True)
    render = programs.add_parser("render", help="the real-time renderer's image")
    reference = programs.add_parser("reference", help="the path-traced reference")
    for program in (render, reference):
        program.add_argument("scene", help="a scene file, or a shipped scene's name")
        program.add_argument("--size", type=_size, default=(512, 512) if program is render
                             else (256, 256), help="WIDTHxHEIGHT")
        program.add_argument("--set", type=_setting, action="append", default=[],
                             metavar="NAME=VALUE", help="a method setting")
        program.add_argument("-o", "--output", required=True, help=".exr or .png")
    render.add_argument("--frames", type=int, default=1)
    render.add_argument("--view", default="final")
    render.add_argument("--time", type=float)
    reference.add_argument("--spp", type=int, default=65536)
    reference.add_argument("--noise", type=float, default=0.01)
    reference.add_argument("--seed", type=int, default=1)
    compare = programs.add_parser("compare", help="the error figures of A against reference B")
    compare.add_argument("a")
    compare.add_argument("b")
    compare.add_argument("--exposure", type=float, default=1.0)
    compare.add_argument("--max-diff", type=float)
    args = parser.parse_args(argv)
    try:
        if args.program == "compare":
            figures = ssgi.compare(args.a, args.b, exposure=args.exposure,
                                   max_diff=args.max_diff, maps=False)
            for name, value in figures.items():
                print(f"{name}: {value}")
            return 0
        scene = _scene(args.scene, args.set)
        if args.program == "render":
            with ssgi.Renderer(scene, args.size, view=args.view) as renderer:
                if args.time is not None:
                    renderer.set_time(args.time)
                image = renderer.render(frames=args.frames)
        else:
            image = ssgi.reference(scene, args.size, spp=args.spp, noise=args.noise,
                                   seed=args.seed)
        ssgi.write_image(args.output, image)
        print(f"wrote {args.output}")
        return 0
    except (ssgi.InputError, ssgi.ArgumentTypeError) as error:
        print(f"error: {error}", file=sys.stderr)
        return 2
    except ssgi.Error as error:
        print(f"error: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
