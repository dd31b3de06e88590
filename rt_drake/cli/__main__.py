"""``python -m rt_drake.cli``: the ``rt-drake`` command without the script."""

from rt_drake.cli import main_exit

if __name__ == "__main__":
    main_exit()
