#!/usr/bin/env python3
"""Writes the APT replay transcripts of tests/devices/tst_apt_replay.cpp.

Every byte is laid out here from the message tables of the "Thorlabs APT Controllers
Host-Controller Communications Protocol" (issue 25), independently of the C++ codec, so the
replay tests check the codec and the Stage against the document, not against themselves.
The behaviours are those seen on real controllers (see each transcript's header comment).
Run from this directory: python3 make_transcripts.py
"""
import struct

HOST, USB = 0x01, 0x50


def short(msg_id, p1=0, p2=0, dest=USB, src=HOST):
    return struct.pack("<HBBBB", msg_id, p1, p2, dest, src)


def long(msg_id, data, dest=HOST, src=USB):
    return struct.pack("<HHBB", msg_id, len(data), dest | 0x80, src) + data


def hexs(b):
    return " ".join("%02X" % x for x in b)


def text(s, n):
    return s.encode().ljust(n, b"\0")


class Device:
    def __init__(self, model, serial, stepper, counts, vel_scale, acc_scale, hw_type):
        self.model, self.serial, self.stepper = model, serial, stepper
        self.counts, self.vel_scale, self.acc_scale, self.hw_type = counts, vel_scale, acc_scale, hw_type

    def pos(self, units):
        return int(round(units * self.counts))

    def vel(self, v):
        return int(round(v * self.vel_scale))

    def acc(self, a):
        return int(round(a * self.acc_scale))


# Scale factors from the document's conversion section (stage_models.h repeats them):
# KDC101 + Z8: T = 2048 / 6e6 s, V_apt = EncCnt T 65536 V, A_apt = EncCnt T^2 65536 A.
T = 2048.0 / 6e6
KDC101 = Device("KDC101", 27000001, False, 34304.0, 34304.0 * T * 65536, 34304.0 * T * T * 65536, 44)
# K10CR1 (Trinamic stepper): V_apt = 53.68 EncCnt V, A_apt = 53.68 x 204.94e-6 EncCnt A.
K10 = 409600.0 / 3.0
K10CR1 = Device("K10CR1", 55000001, True, K10, 53.68 * K10, 53.68 * 204.94e-6 * K10, 45)

ENABLED, HOMED, CONNECTED, SETTLED = 0x80000000, 0x400, 0x100, 0x2000
FWD_LIMIT, MOVING_FWD, MOVING_REV = 0x1, 0x10, 0x20
IDLE = ENABLED | HOMED | CONNECTED | SETTLED


class Transcript:
    def __init__(self, dev, header):
        self.dev, self.lines, self.t = dev, ["# " + l for l in header.strip().splitlines()], 0.0

    def tx(self, b, dt=0.0):
        self.t += dt
        self.lines.append("%.6f TX %s" % (self.t, hexs(b)))

    def rx(self, b, dt=0.002):
        self.t += dt
        self.lines.append("%.6f RX %s" % (self.t, hexs(b)))

    def unplug(self, dt):
        self.t += dt
        self.lines.append("%.6f UNPLUG" % self.t)

    def note(self, s):
        self.lines.append("# " + s)

    def status(self, position, bits, velocity=0):
        d = self.dev
        if d.stepper:  # MOT_GET_STATUSUPDATE 0x0481: chan, position, encoder count, status bits
            return long(0x0481, struct.pack("<HllL", 1, d.pos(position), d.pos(position), bits))
        # MOT_GET_DCSTATUSUPDATE 0x0491: chan, position, velocity word, reserved word, bits
        return long(0x0491, struct.pack("<HlHHL", 1, d.pos(position), velocity & 0xFFFF, 0, bits))

    def completion(self, msg_id, position, bits):
        # MOVE_COMPLETED 0x0464 / MOVE_STOPPED 0x0466: the DC status layout; steppers send a
        # zero velocity word.
        return long(msg_id, struct.pack("<HlHHL", 1, self.dev.pos(position), 0, 0, bits))

    def connect(self, position, velocity, accel, jog_step, home_velocity):
        d = self.dev
        self.note("connect: HW info, enable state, velocity, jog, home, limit-switch parameters, status")
        self.tx(short(0x0005))  # HW_REQ_INFO
        info = struct.pack("<l", d.serial) + text(d.model, 8) + struct.pack("<H", d.hw_type)
        info += bytes([0, 1, 3, 0]) + text("", 48) + text("", 12) + struct.pack("<HHH", 1, 0, 1)
        self.rx(long(0x0006, info))  # HW_GET_INFO, 84 bytes
        self.tx(short(0x0211, 1))  # MOD_REQ_CHANENABLESTATE
        self.rx(short(0x0212, 1, 0x01, dest=HOST, src=USB))  # enabled
        self.tx(short(0x0414, 1))  # MOT_REQ_VELPARAMS
        self.rx(long(0x0415, struct.pack("<Hlll", 1, 0, d.acc(accel), d.vel(velocity))))
        self.tx(short(0x0417, 1))  # MOT_REQ_JOGPARAMS: single step, profiled stop
        self.rx(long(0x0418, struct.pack("<HHllllH", 1, 2, d.pos(jog_step), 0, d.acc(accel), d.vel(velocity / 2), 2)))
        self.tx(short(0x0441, 1))  # MOT_REQ_HOMEPARAMS: reverse, reverse switch
        self.rx(long(0x0442, struct.pack("<HHHll", 1, 2, 1, d.vel(home_velocity), 0)))
        self.tx(short(0x0424, 1))  # MOT_REQ_LIMSWITCHPARAMS: both switches make on contact
        self.rx(long(0x0425, struct.pack("<HHHLLH", 1, 2, 2, 0, 0, 1)))
        self.poll(position, IDLE)

    def poll(self, position, bits, dt=0.0):
        self.tx(short(0x0480 if self.dev.stepper else 0x0490, 1), dt)
        self.rx(self.status(position, bits))

    def move_abs(self, position):
        self.tx(long(0x0453, struct.pack("<Hl", 1, self.dev.pos(position)), dest=USB, src=HOST))

    def write(self, path):
        with open(path, "w") as f:
            f.write("\n".join(self.lines) + "\n")


def completion_moving_bits():
    t = Transcript(K10CR1, """
K10CR1: MOVE_COMPLETED carries status 0x80000030 (both moving bits set, homed clear)
although the move is over, as a real K10CR1 sends it. The host must take the state from
the status poll that follows (homed, at rest), so the second move is accepted.""")
    t.connect(0.0, 10.0, 10.0, 1.0, 5.0)
    t.note("move to 10 deg: 2 s trapezoid; completion with the moving bits")
    t.move_abs(10.0)
    t.rx(t.completion(0x0464, 10.0, ENABLED | MOVING_FWD | MOVING_REV), 2.0)
    t.poll(10.0, IDLE)
    t.note("second move to 20 deg: accepted because the poll said homed")
    t.move_abs(20.0)
    t.rx(t.completion(0x0464, 20.0, ENABLED | MOVING_FWD | MOVING_REV), 2.0)
    t.poll(20.0, IDLE)
    t.write("k10cr1-completion-moving-bits.apt")


def error_response():
    t = Transcript(KDC101, """
KDC101: the controller refuses a move with HW_RICHRESPONSE (0x0081, 68 bytes: id of the
offending message, error code, 64 characters of text). Code and text are illustrative;
the host must end the wait with them at once, not after its timeout.""")
    t.connect(0.0, 2.0, 1.5, 0.1, 1.0)
    t.move_abs(5.0)
    t.rx(long(0x0081, struct.pack("<HH", 0x0453, 0x0011) + text("Motor drive fault: check the stage cable", 64)), 0.004)
    t.write("kdc101-error-response.apt")


def short_form():
    t = Transcript(KDC101, """
Host side of the header-only moves, replayed against the emulator: SET_MOVEABSPARAMS then
the 6-byte MOVE_ABSOLUTE header 53 04 01 00 50 01 moves to the stored position;
SET_MOVERELPARAMS then 48 04 01 00 50 01 moves by the stored distance. The emulator must
answer each with MOVE_COMPLETED at the right position (status: enabled, homed, settled).""")
    d = KDC101
    t.tx(long(0x0450, struct.pack("<Hl", 1, d.pos(5.0)), dest=USB, src=HOST))  # SET_MOVEABSPARAMS 5 mm
    t.tx(short(0x0453, 1))
    t.rx(t.completion(0x0464, 5.0, IDLE), 4.0)
    t.tx(long(0x0445, struct.pack("<Hl", 1, d.pos(1.0)), dest=USB, src=HOST))  # SET_MOVERELPARAMS 1 mm
    t.tx(short(0x0448, 1))
    t.rx(t.completion(0x0464, 6.0, IDLE), 2.0)
    t.write("kdc101-short-form.apt")


def limit_switch_hit():
    t = Transcript(KDC101, """
KDC101: a move to 20 mm hits the forward limit switch at 12.3 mm: MOVE_STOPPED (not
MOVE_COMPLETED) with the forward-limit bit; the poll that follows shows the switch closed.""")
    t.connect(0.0, 2.0, 1.5, 0.1, 1.0)
    t.move_abs(20.0)
    t.rx(t.completion(0x0466, 12.3, ENABLED | HOMED | CONNECTED | FWD_LIMIT), 6.0)
    t.poll(12.3, IDLE | FWD_LIMIT)
    t.write("kdc101-limit-switch-hit.apt")


def unplug():
    t = Transcript(KDC101, """
KDC101: the USB cable is pulled 1 s into a move to 20 mm. The host must report the
disconnection, mark the position unknown and send nothing more.""")
    t.connect(0.0, 2.0, 1.5, 0.1, 1.0)
    t.move_abs(20.0)
    t.unplug(1.0)
    t.write("kdc101-unplug-mid-move.apt")


for make in (completion_moving_bits, error_response, short_form, limit_switch_hit, unplug):
    make()
