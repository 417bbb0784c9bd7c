#!/usr/bin/env python3
"""An independent XTF reader, written from Triton Imaging's "eXtended Triton Format (XTF)" specification
(Rev. 41) with numpy structured types, sharing no code with the library: it decodes the files that
tests/io/python/fixture.cpp wrote and compares them with what the fixture says they hold (expected.txt and the
raw waterfall). Exit status 0 when every check holds, 1 otherwise."""
import math
import sys

import numpy as np

LE = "<"
FILE_HEADER = np.dtype({
    "names": ["FileFormat", "SystemType", "RecordingProgramName", "RecordingProgramVersion", "SonarName",
              "SonarType", "NoteString", "ThisFileName", "NavUnits", "NumberOfSonarChannels",
              "NumberOfBathymetryChannels", "NumberOfSnippetChannels", "NumberOfForwardLookArrays",
              "NumberOfEchoStrengthChannels", "NumberOfInterferometryChannels"],
    "formats": ["u1", "u1", "S8", "S8", "S16", LE + "u2", "S64", "S64", LE + "u2", LE + "u2", LE + "u2", "u1", "u1",
                LE + "u2", "u1"],
    "offsets": [0, 1, 2, 10, 18, 34, 36, 100, 164, 166, 168, 170, 171, 172, 174],
    "itemsize": 256})
CHANINFO = np.dtype({
    "names": ["TypeOfChannel", "SubChannelNumber", "CorrectionFlags", "UniPolar", "BytesPerSample", "ChannelName",
              "VoltScale", "Frequency", "HorizBeamAngle", "TiltAngle", "BeamWidth", "SampleFormat"],
    "formats": ["u1", "u1", LE + "u2", LE + "u2", LE + "u2", "S16", LE + "f4", LE + "f4", LE + "f4", LE + "f4",
                LE + "f4", "u1"],
    "offsets": [0, 1, 2, 4, 6, 12, 28, 32, 36, 40, 44, 74],
    "itemsize": 128})
PING_HEADER = np.dtype({
    "names": ["MagicNumber", "HeaderType", "SubChannelNumber", "NumChansToFollow", "NumBytesThisRecord", "Year",
              "Month", "Day", "Hour", "Minute", "Second", "HSeconds", "JulianDay", "PingNumber", "SoundVelocity",
              "SensorSpeed", "SensorYcoordinate", "SensorXcoordinate", "SensorPrimaryAltitude", "SensorPitch",
              "SensorRoll", "SensorHeading", "Heave"],
    "formats": [LE + "u2", "u1", "u1", LE + "u2", LE + "u4", LE + "u2", "u1", "u1", "u1", "u1", "u1", "u1",
                LE + "u2", LE + "u4", LE + "f4", LE + "f4", LE + "f8", LE + "f8", LE + "f4", LE + "f4", LE + "f4",
                LE + "f4", LE + "f4"],
    "offsets": [0, 2, 3, 4, 10, 14, 16, 17, 18, 19, 20, 21, 22, 28, 32, 152, 160, 168, 196, 204, 208, 212, 216],
    "itemsize": 256})
CHAN_HEADER = np.dtype({
    "names": ["ChannelNumber", "SlantRange", "GroundRange", "TimeDelay", "TimeDuration", "SecondsPerPing",
              "Frequency", "NumSamples", "Weight"],
    "formats": [LE + "u2", LE + "f4", LE + "f4", LE + "f4", LE + "f4", LE + "f4", LE + "u2", LE + "u4", LE + "i2"],
    "offsets": [0, 4, 8, 12, 16, 20, 26, 42, 58],
    "itemsize": 64})

failures = []


def check(ok, what):
    if not ok:
        failures.append(what)


def read_xtf(path):
    data = open(path, "rb").read()
    head = np.frombuffer(data, FILE_HEADER, 1, 0)[0]
    channels = np.frombuffer(data, CHANINFO, 6, 256)
    n_sonar = int(head["NumberOfSonarChannels"])
    pings = []
    offset = 1024
    lengths = []
    while offset < len(data):
        ping = np.frombuffer(data, PING_HEADER, 1, offset)[0]
        check(ping["MagicNumber"] == 0xFACE, f"{path}: magic at {offset}")
        length = int(ping["NumBytesThisRecord"])
        lengths.append(length)
        at = offset + 256
        lines = {}
        for _ in range(int(ping["NumChansToFollow"])):
            ch = np.frombuffer(data, CHAN_HEADER, 1, at)[0]
            info = channels[int(ch["ChannelNumber"])]
            bps = int(info["BytesPerSample"])
            kind = {1: "u1", 2: LE + "u2"}.get(bps, LE + "f4")
            samples = np.frombuffer(data, kind, int(ch["NumSamples"]), at + 64).astype(np.float64)
            if bps != 4:
                samples = samples * 2.0 ** (-int(ch["Weight"]))
            lines[int(info["TypeOfChannel"])] = (ch, samples)
            at += 64 + bps * int(ch["NumSamples"])
        check(at <= offset + length, f"{path}: channels overrun the record at {offset}")
        pings.append((ping, lines))
        offset += length
    check(offset == len(data), f"{path}: record lengths sum to {offset}, file has {len(data)} bytes")
    return head, channels[:n_sonar], pings, lengths


def main():
    expected = {}
    positions = {}
    for line in open("expected.txt"):
        parts = line.split()
        if parts[0] == "position":
            positions[int(parts[1])] = (float(parts[2]), float(parts[3]))
        else:
            expected[parts[0]] = float(parts[1])
    n_pings, n = int(expected["pings"]), int(expected["samples"])
    waterfall = np.fromfile("waterfall_f64.raw", dtype=LE + "f8").reshape(n_pings, 2 * n)
    lat0, lon0 = math.radians(expected["origin_lat_deg"]), expected["origin_lon_deg"]
    # WGS 84 radii of curvature at the origin: meridian M and prime vertical N.
    a, f = 6378137.0, 1 / 298.257223563
    e2 = f * (2 - f)
    w = 1 - e2 * math.sin(lat0) ** 2
    m_lat, m_lon = a * (1 - e2) / w ** 1.5, a / math.sqrt(w) * math.cos(lat0)
    for name, bps, fmt, nav in (("sss_f32.xtf", 4, 5, 3), ("sss_u16.xtf", 2, 3, 0), ("sss_u8.xtf", 1, 8, 0)):
        head, channels, pings, lengths = read_xtf(name)
        check(head["FileFormat"] == 0x7B and head["SystemType"] == 1, f"{name}: FileFormat/SystemType")
        check(head["RecordingProgramVersion"] == b"223", f"{name}: version")
        check(head["NavUnits"] == nav, f"{name}: NavUnits {head['NavUnits']}")
        check(len(channels) == 2, f"{name}: {len(channels)} sonar channels")
        check([int(c["TypeOfChannel"]) for c in channels] == [1, 2], f"{name}: channel types")
        for c in channels:
            check(c["BytesPerSample"] == bps and c["SampleFormat"] == fmt, f"{name}: sample format")
            check(c["Frequency"] == np.float32(expected["frequency_khz"]), f"{name}: frequency")
            check(c["BeamWidth"] == np.float32(expected["beam_width_deg"]), f"{name}: beam width")
            check(c["TiltAngle"] == np.float32(expected["tilt_deg"]), f"{name}: tilt")
            check(c["HorizBeamAngle"] == np.float32(expected["horizontal_beam_angle_deg"]), f"{name}: beam angle")
        check(len(pings) == n_pings, f"{name}: {len(pings)} pings")
        check(all(L % 64 == 0 for L in lengths), f"{name}: packets padded to 64 bytes")
        for i, (ping, lines) in enumerate(pings):
            check(ping["HeaderType"] == 0 and ping["NumChansToFollow"] == 2, f"{name}: ping {i} type")
            check(ping["PingNumber"] == expected["first_ping"] + i, f"{name}: ping number {i}")
            t = expected["start_unix_s"] + i * expected["ping_interval_s"]
            day, rest = divmod(round(t * 100), 8640000)
            date = np.datetime64(int(day), "D").astype(object)
            check((ping["Year"], ping["Month"], ping["Day"]) == (date.year, date.month, date.day),
                  f"{name}: date of ping {i}")
            check(ping["JulianDay"] == date.timetuple().tm_yday, f"{name}: day of year of ping {i}")
            got = ping["Hour"] * 360000 + ping["Minute"] * 6000 + ping["Second"] * 100 + ping["HSeconds"]
            check(got == rest, f"{name}: time of day of ping {i}: {got} vs {rest}")
            check(ping["SoundVelocity"] == 750.0, f"{name}: SoundVelocity (half the speed)")
            check(abs(ping["SensorSpeed"] - expected["speed_mps"] * 3600 / 1852) < 1e-4, f"{name}: speed in knots")
            check(abs(ping["SensorHeading"] - expected["heading_deg"]) < 1e-4, f"{name}: heading")
            check(ping["SensorPrimaryAltitude"] == np.float32(expected["altitude_m"]), f"{name}: altitude")
            x, y = positions[i]
            if nav == 3:
                lat = expected["origin_lat_deg"] + math.degrees(y / m_lat)
                lon = lon0 + math.degrees(x / m_lon)
                check(abs(ping["SensorYcoordinate"] - lat) < 1e-9, f"{name}: latitude of ping {i}")
                check(abs(ping["SensorXcoordinate"] - lon) < 1e-9, f"{name}: longitude of ping {i}")
            else:
                check(ping["SensorYcoordinate"] == y and ping["SensorXcoordinate"] == x, f"{name}: position {i}")
            port_header, port = lines[1]
            stbd_header, stbd = lines[2]
            check(port_header["ChannelNumber"] == 0 and stbd_header["ChannelNumber"] == 1, f"{name}: channel numbers")
            slant = n * expected["dt_s"] * 750.0
            check(abs(port_header["SlantRange"] - slant) < 1e-3 * slant, f"{name}: slant range")
            check(abs(port_header["GroundRange"] - math.sqrt(slant ** 2 - 81.0)) < 1e-3 * slant, f"{name}: ground")
            check(len(port) == n and len(stbd) == n, f"{name}: sample counts")
            # Port far-to-near then starboard near-to-far is the waterfall's row, left to right.
            row = np.concatenate([port, stbd])
            truth = waterfall[i]
            if bps == 4:
                check(np.array_equal(row, truth.astype(np.float32).astype(np.float64)), f"{name}: samples of ping {i}")
            else:
                step = 2.0 ** (-int(port_header["Weight"]))
                err = np.max(np.abs(row - truth))
                check(err <= 0.5 * step * (1 + 1e-9), f"{name}: ping {i} off by {err / step} steps")
                top = 255 if bps == 1 else 65535
                check(waterfall.max() / step <= top and waterfall.max() / step > top / 2, f"{name}: weight")
    if failures:
        print("\n".join(failures))
        return 1
    print(f"independent reader: 3 XTF files, {n_pings} pings x 2 x {n} samples each, all fields agree")
    return 0


if __name__ == "__main__":
    sys.exit(main())
