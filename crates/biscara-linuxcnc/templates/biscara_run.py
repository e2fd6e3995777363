#!/usr/bin/python3
"""The headless display of this LinuxCNC configuration (written by `biscara linuxcnc config`).

LinuxCNC starts it as its [DISPLAY] program and shuts down when it exits. It turns the machine
on, homes it (each joint where it stands), then plays a joint trajectory through the stream path
and/or runs a G-code program, recording every servo cycle with halsampler. What to do comes
from the environment (`biscara linuxcnc run` sets it):

  BISCARA_PROGRAM  a G-code program to run (absolute path)
  BISCARA_STREAM   a file of joint samples to play first through the stream path, one line per
                   servo cycle: theta1 theta2 d4 theta3 (degrees, mm)
  BISCARA_ORIGIN   "X,Y,Z,C": a G54 offset set before the program (mm, degrees)
  BISCARA_SAMPLES  where to write the recorded samples (halsampler -t's lines; default
                   samples.txt)
  BISCARA_RESULT   where to write the outcome as JSON (default result.json)
  BISCARA_TIMEOUT  seconds to wait for the program or the stream to end (default 3600)
  BISCARA_EVENT    "estop:SECONDS" or "machine-off:SECONDS": press E-stop (or switch the machine
                   off) that long after the stream (or the program) started
"""

import json
import os
import subprocess
import time

import linuxcnc

STAT = linuxcnc.stat()
COMMAND = linuxcnc.command()
ERRORS = linuxcnc.error_channel()
MESSAGES = []
RESULT = {"ok": False, "messages": MESSAGES, "line": 0}


class Stopped(Exception):
    """LinuxCNC reported an error, or something took too long."""


def collect_messages():
    """Keeps every message LinuxCNC sent since the last call; True when one was an error."""
    failed = False
    while True:
        message = ERRORS.poll()
        if not message:
            return failed
        kind, text = message
        error = kind in (linuxcnc.NML_ERROR, linuxcnc.OPERATOR_ERROR) and not text.startswith("Note:")
        MESSAGES.append({"error": error, "text": text})
        failed = failed or error


def wait_for(condition, what, timeout=10.0):
    """Polls LinuxCNC's status until condition() holds; raises Stopped on an error or timeout."""
    deadline = time.monotonic() + timeout
    while True:
        STAT.poll()
        if condition():
            return
        line = max(STAT.motion_line, STAT.current_line)
        if line > 0:
            RESULT["line"] = line
        if collect_messages():
            raise Stopped(f"LinuxCNC stopped while waiting for {what}")
        if time.monotonic() > deadline:
            raise Stopped(f"timed out after {timeout:g} s waiting for {what}")
        time.sleep(0.002)


def halcmd(*words):
    subprocess.run(["halcmd", *words], check=True, stdout=subprocess.DEVNULL)


def hal_value(name):
    return subprocess.run(["halcmd", "getp", name], check=True, capture_output=True,
                          text=True).stdout.strip()


def hal_signal(name):
    return subprocess.run(["halcmd", "gets", name], check=True, capture_output=True,
                          text=True).stdout.strip()


def start_machine():
    wait_for(lambda: STAT.task_state != 0, "LinuxCNC's task")
    COMMAND.state(linuxcnc.STATE_ESTOP_RESET)
    wait_for(lambda: STAT.task_state == linuxcnc.STATE_ESTOP_RESET, "E-stop reset")
    COMMAND.state(linuxcnc.STATE_ON)
    wait_for(lambda: STAT.task_state == linuxcnc.STATE_ON, "machine on")
    COMMAND.mode(linuxcnc.MODE_MANUAL)
    wait_for(lambda: STAT.task_mode == linuxcnc.MODE_MANUAL, "manual mode")
    COMMAND.home(-1)
    wait_for(lambda: all(STAT.homed[:STAT.joints]), "homing", 30.0)


def fire(event):
    """Presses E-stop or switches the machine off: the commissioning event of the run."""
    if event == "estop":
        COMMAND.state(linuxcnc.STATE_ESTOP)
    else:
        COMMAND.state(linuxcnc.STATE_OFF)


def stop_cause():
    """Why the stream's latch fell."""
    STAT.poll()
    if hal_signal("stream-ferror") == "TRUE":
        return "following error"
    if STAT.task_state == linuxcnc.STATE_ESTOP:
        return "E-stop"
    if not STAT.enabled:
        return "machine off"
    return "joint fault"


def stream_trajectory(path, timeout, keep_recording, event):
    """Plays the samples in path through streamer -> limit3 -> mux2 with the machine on, inside
    the enable chain (biscara.hal's stream-latch); afterwards the machine is turned off and on so
    that LinuxCNC takes up where the joints are. Returns the event that stopped it, if one did."""
    with open(path) as samples:
        feeder = subprocess.Popen(["halstreamer"], stdin=samples)
    full = int(hal_value("streamer.0.curr-depth")) + 1
    wait_for(lambda: feeder.poll() is not None or int(hal_value("streamer.0.curr-depth")) > full // 2,
             "the stream to fill")
    halcmd("sets", "record", "1")
    halcmd("sets", "stream-own-fb", "1")
    halcmd("sets", "stream-on", "1")
    halcmd("sets", "stream-request", "1")
    # The latch sets in the next servo cycle: with the machine on and no following error.
    wait_for(lambda: hal_value("stream-latch.ok-out") == "TRUE",
             "the stream's enable (machine on, out of E-stop, no following error)", 1.0)
    start = time.monotonic()
    deadline = start + timeout
    fired = None
    while True:
        elapsed = time.monotonic() - start
        if event and fired is None and elapsed >= event[1]:
            fire(event[0])
            fired = elapsed
        if feeder.poll() is not None and hal_value("streamer.0.curr-depth") == "0":
            break
        if hal_value("stream-latch.ok-out") != "TRUE":
            cause = stop_cause()
            what = {"estop": "E-stop", "machine-off": "machine off"}.get(event[0]) if fired else cause
            RESULT["event"] = {"what": what, "time": fired if fired is not None else elapsed}
            collect_messages()
            # What the joints do after the stop, recorded: they hold.
            time.sleep(0.3)
            feeder.kill()
            feeder.wait()
            return True
        if time.monotonic() > deadline:
            raise Stopped(f"timed out after {timeout:g} s waiting for the stream's end")
        time.sleep(0.002)
    halcmd("sets", "stream-request", "0")
    if not keep_recording:
        halcmd("sets", "record", "0")
    if feeder.returncode != 0:
        raise Stopped(f"halstreamer failed with exit code {feeder.returncode}")
    # LinuxCNC takes up where the joints are: off (its command follows the feedback), the
    # feedback its own again, the joints' muxes back to its command, on.
    COMMAND.state(linuxcnc.STATE_OFF)
    wait_for(lambda: not STAT.enabled, "machine off")
    halcmd("sets", "stream-own-fb", "0")
    time.sleep(0.05)
    halcmd("sets", "stream-on", "0")
    COMMAND.state(linuxcnc.STATE_ON)
    wait_for(lambda: STAT.task_state == linuxcnc.STATE_ON, "machine on")
    return False


def run_program(path, origin, timeout, event):
    COMMAND.mode(linuxcnc.MODE_MDI)
    wait_for(lambda: STAT.task_mode == linuxcnc.MODE_MDI, "MDI mode")
    if origin:
        x, y, z, c = origin.split(",")
        COMMAND.mdi(f"G10 L2 P1 X{x} Y{y} Z{z} C{c}")
        wait_for(lambda: STAT.interp_state == linuxcnc.INTERP_IDLE, "the G54 offset")
    COMMAND.mode(linuxcnc.MODE_AUTO)
    wait_for(lambda: STAT.task_mode == linuxcnc.MODE_AUTO, "auto mode")
    COMMAND.program_open(path)
    halcmd("sets", "record", "1")
    COMMAND.auto(linuxcnc.AUTO_RUN, 0)
    wait_for(lambda: STAT.interp_state != linuxcnc.INTERP_IDLE, "the program to start")
    if event:
        start = time.monotonic()
        wait_for(lambda: time.monotonic() - start >= event[1]
                 or (STAT.interp_state == linuxcnc.INTERP_IDLE and STAT.queue == 0),
                 "the event", timeout)
        if time.monotonic() - start >= event[1]:
            fired = time.monotonic() - start
            fire(event[0])
            what = {"estop": "E-stop", "machine-off": "machine off"}[event[0]]
            RESULT["event"] = {"what": what, "time": fired}
            time.sleep(0.3)
            collect_messages()
            halcmd("sets", "record", "0")
            return True
    wait_for(lambda: STAT.interp_state == linuxcnc.INTERP_IDLE and STAT.queue == 0,
             "the program's end", timeout)
    halcmd("sets", "record", "0")
    return False


def main():
    program = os.environ.get("BISCARA_PROGRAM")
    stream = os.environ.get("BISCARA_STREAM")
    timeout = float(os.environ.get("BISCARA_TIMEOUT", "3600"))
    event = os.environ.get("BISCARA_EVENT")
    if event:
        kind, at = event.split(":")
        event = (kind, float(at))
    with open(os.environ.get("BISCARA_SAMPLES", "samples.txt"), "w") as samples:
        sampler = subprocess.Popen(["halsampler", "-t"], stdout=samples)
    try:
        start_machine()
        stopped = False
        if stream:
            stopped = stream_trajectory(stream, timeout, bool(program), event)
        if program and not stopped:
            stopped = run_program(program, os.environ.get("BISCARA_ORIGIN"), timeout, event)
        failed = collect_messages()
        RESULT["ok"] = not failed and not stopped
    except Stopped as stopped:
        RESULT["failure"] = str(stopped)
    except Exception as error:
        RESULT["failure"] = f"the headless display failed: {error!r}"
    finally:
        try:
            halcmd("sets", "record", "0")
            halcmd("sets", "stream-request", "0")
            # halsampler empties the sampler's FIFO before it is stopped.
            deadline = time.monotonic() + 10.0
            while hal_value("sampler.0.curr-depth") != "0" and time.monotonic() < deadline:
                time.sleep(0.01)
            RESULT["overruns"] = int(hal_value("sampler.0.overruns"))
            RESULT["underruns"] = int(hal_value("streamer.0.underruns"))
        finally:
            sampler.terminate()
            sampler.wait()
            collect_messages()
            with open(os.environ.get("BISCARA_RESULT", "result.json"), "w") as out:
                json.dump(RESULT, out)


if __name__ == "__main__":
    main()
