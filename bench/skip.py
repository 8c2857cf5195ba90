"""A bench part that measures something this project cannot build or run
here on its own (the Pico W firmware under emulation needs the pico-sdk and
a bootrom) raises Skipped: reported, not a failure of make bench."""


class Skipped(Exception):
    pass
