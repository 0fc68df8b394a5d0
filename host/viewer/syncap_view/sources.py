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


# Every event of an LCM log starts with this word (then eventnum, timestamp, channel and data
# lengths, channel, data): where the framing breaks, reading goes on at the next one.
LOG_SYNC = b"\xed\xa1\xda\x01"


def _next_sync(path: str, start: int) -> int | None:
    """The offset of the first sync word at or after `start`, or None."""
    with open(path, "rb") as f:
        f.seek(start)
        tail = f.read()
    at = tail.find(LOG_SYNC)
    return None if at < 0 else start + at


def log_events(path: str, channel_regex: str, errors: list) -> Iterator[tuple[str, bytes, str]]:
    """The events of an LCM log whose channel matches. Where the log's framing breaks (bytes
    that are not an event: a disk error, a file cut and joined), reading resumes at the next
    event and the bytes skipped go to `errors`; a log that ends inside an event (a recorder
    killed mid-write) ends there with an entry in `errors`. A file with no event at all is an
    InputError."""
    if not os.path.isfile(path):
        raise InputError(f"lcmlog:{path}: no such file")
    size = os.path.getsize(path)
    try:
        log = lcm.EventLog(path, "r")
    except (IOError, OSError, ValueError) as e:
        raise InputError(f"lcmlog:{path}: cannot open: {e}") from None
    pattern = re.compile(channel_regex)
    count, good_end = 0, 0  # events read; the offset after the last one
    try:
        while True:
            try:
                event = log.read_next_event()
            except (IOError, OSError, ValueError):
                event = None
            if event is not None:
                count += 1
                good_end = log.tell()
                if pattern.fullmatch(event.channel):
                    yield event.channel, event.data, f"lcmlog:{path} event {event.eventnum}"
                continue
            if good_end >= size:
                return
            resume = _next_sync(path, good_end + 1)
            if resume is None:
                if count == 0:
                    raise InputError(f"lcmlog:{path}: no LCM log event in its {size} bytes "
                                     "(not an LCM log?)")
                errors.append(f"lcmlog:{path} after event {count}: the log ends inside an "
                              f"event (its last {size - good_end} bytes not shown)")
                return
            errors.append(f"lcmlog:{path} after event {count}: bytes {good_end}..{resume - 1} "
                          "are not an event; skipped to the next one")
            log.seek(resume)
            good_end = resume
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


def live_events(url: str | None, channel_regex: str, poll_ms: int = 100,
                stop=lambda: False) -> Iterator[tuple[str, bytes, str] | None]:
    """Messages as they arrive; None every `poll_ms` without one, so that the caller can look
    up. Ends when `stop()` turns true (Ctrl-C, SIGTERM: the signal handler sets it rather than
    raising inside LCM's C wait, which left the interpreter with an exception it could not
    report). LCM matches channel regexes whole, as here."""
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
    while not stop():
        if not queue:
            try:
                lc.handle_timeout(poll_ms)
            except OSError:  # the wait interrupted by a signal
                if stop():
                    return
                raise
        if queue:
            while queue:
                yield queue.popleft()
        else:
            yield None
