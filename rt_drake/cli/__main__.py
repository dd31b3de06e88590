"""``python -m rt_drake.cli``: the ``rt-drake`` command."""

from rt_drake.cli import main_exit

main_exit()
