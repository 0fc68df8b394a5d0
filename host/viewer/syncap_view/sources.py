"""Where messages come from: a recorded LCM log (lcm.EventLog) or live LCM.

Each yields (channel, data, where), `where` naming the input and the place of the message in it,
for the error messages: "lcmlog:FILE event 12", "udpm://... message 3".
"""

from __future__ import annotations

import collections
import os
import re
import sys
from typing import Iterator

import lcm


class InputError(RuntimeError):
    """The input cannot be opened or read on (named in the message)."""


def log_events(path: str, channel_regex: str, errors: list) -> Iterator[tuple[str, bytes, str]]:
    """The events of an LCM log whose channel matches. A log that ends inside an event (a
    recorder killed mid-write) or whose framing breaks ends here with an entry in `errors`: what
    came before is still shown."""
    if not os.path.isfile(path):
        raise InputError(f"lcmlog:{path}: no such file")
    try:
        log = lcm.EventLog(path, "r")
    except (IOError, OSError, ValueError) as e:
        raise InputError(f"lcmlog:{path}: cannot open: {e}") from None
    pattern = re.compile(channel_regex)
    count = 0
    try:
        while True:
            try:
                event = log.read_next_event()
            except (IOError, OSError, ValueError) as e:  # framing broken mid-file
                errors.append(f"lcmlog:{path} after event {count}: the log does not read on "
                              f"({e}); the rest of the file is not shown")
                return
            if event is None:
                return
            count += 1
            if pattern.fullmatch(event.channel):
                yield event.channel, event.data, f"lcmlog:{path} event {event.eventnum}"
    finally:
        log.close()


def group_lines(path: str) -> Iterator[tuple[str, str]]:
    """The host's JSON lines, one frame group a line: (line, "FILE:N")."""
    try:
        f = open(path, encoding="utf-8", errors="replace")
    except OSError as e:
        raise InputError(f"{path}: cannot open: {e.strerror}") from None

    def lines():
        with f:
            for number, line in enumerate(f, 1):
                if line.strip():
                    yield line, f"{path}:{number}"
    return lines()


def live_events(url: str | None, channel_regex: str, poll_ms: int = 100
                ) -> Iterator[tuple[str, bytes, str] | None]:
    """Messages as they arrive; None every `poll_ms` without one, so that the caller can look
    up. Ends on KeyboardInterrupt in the caller. LCM matches channel regexes whole, as here."""
    try:
        lc = lcm.LCM(url) if url else lcm.LCM()
    except (IOError, OSError, RuntimeError) as e:
        raise InputError(f"{url or 'the LCM default URL'}: cannot open: {e}") from None
    queue: collections.deque = collections.deque()
    name = url or os.environ.get("LCM_DEFAULT_URL") or "LCM default URL"
    count = [0]

    def on_message(channel, data):
        count[0] += 1
        queue.append((channel, data, f"{name} message {count[0]}"))

    lc.subscribe(channel_regex, on_message)
    print(f"syncap view: listening on {name} (Ctrl-C ends)", file=sys.stderr, flush=True)
    while True:
        if not queue:
            lc.handle_timeout(poll_ms)
        if queue:
            while queue:
                yield queue.popleft()
        else:
            yield None
