"""``python -m rt_drake.cli``: the ``rt-drake`` command."""

from rt_drake.cli import main_exit

if __name__ == "__main__":  # importing the module (e.g. walk_packages) runs nothing
    main_exit()
