"""Subcommands of ``rt-drake``: one module each, exposing ``register(subparsers)``."""
