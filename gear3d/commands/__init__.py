"""CLI sub-commands, one module each: ``add_parser(subparsers) -> parser`` and ``run(args) -> int``."""
