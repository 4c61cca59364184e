"""The ``etswarm`` command: a click group whose subcommands load lazily.

Each subsystem keeps its commands in its own module under ``etswarm.cli``; the table
below maps a command name to ``module:attribute``. Loading lazily keeps
``etswarm shapes`` fast (no numba import) and lets each module evolve on its own.
"""

from __future__ import annotations

import importlib
import sys

import click

from etswarm import __version__
from etswarm.errors import EtswarmError

#: command name -> "module:attribute" of a click.Command.
COMMANDS: dict[str, str] = {
    "shapes": "etswarm.cli.shape_commands:shapes",
    "gene": "etswarm.cli.shape_commands:gene",
    "scale": "etswarm.cli.shape_commands:scale",
    "sim": "etswarm.cli.sim_command:sim",
    "run": "etswarm.cli.run_command:run",
    "demo": "etswarm.cli.demo_command:demo",
    "view": "etswarm.cli.viewer_commands:view",
    "replay": "etswarm.cli.viewer_commands:replay",
    "plot": "etswarm.cli.viewer_commands:plot",
    "sweep": "etswarm.cli.experiment_commands:sweep",
    "report": "etswarm.cli.experiment_commands:report",
    "reproduce": "etswarm.cli.experiment_commands:reproduce",
}


def _load(name: str) -> click.Command | None:
    """Import the command ``name``; None when its module is not part of this build."""
    module_name, _, attr = COMMANDS[name].partition(":")
    try:
        module = importlib.import_module(module_name)
    except ModuleNotFoundError as err:
        if err.name == module_name:
            return None
        raise
    return getattr(module, attr, None)


class LazyGroup(click.Group):
    """A group that imports a subcommand's module only when that command is used."""

    def list_commands(self, ctx: click.Context) -> list[str]:
        return [name for name in COMMANDS if _load(name) is not None]

    def get_command(self, ctx: click.Context, cmd_name: str) -> click.Command | None:
        if cmd_name not in COMMANDS:
            return None
        return _load(cmd_name)


@click.group(cls=LazyGroup, context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="etswarm")
def cli() -> None:
    """Simulate Kilobot swarms growing and regrowing shapes with Epigenetic Tracking."""


def usage_error_line(err: click.UsageError) -> str:
    """One line for a bad option or argument: what is wrong, and where the help is."""
    command = err.ctx.command_path if err.ctx is not None else "etswarm"
    return f"{command}: error: {err.format_message()} (see '{command} --help')"


def main(argv: list[str] | None = None) -> None:
    """Console entry point: run the CLI, turning EtswarmError into a one-line message."""
    try:
        cli.main(args=argv, prog_name="etswarm", standalone_mode=False)
    except EtswarmError as err:
        click.echo(f"etswarm: error: {err}", err=True)
        sys.exit(2)
    except click.exceptions.Abort:
        click.echo("etswarm: interrupted", err=True)
        sys.exit(130)
    except click.UsageError as err:
        click.echo(usage_error_line(err), err=True)
        sys.exit(err.exit_code)
    except click.ClickException as err:
        err.show()
        sys.exit(err.exit_code)
    except KeyboardInterrupt:
        click.echo("etswarm: interrupted", err=True)
        sys.exit(130)


if __name__ == "__main__":
    main()
