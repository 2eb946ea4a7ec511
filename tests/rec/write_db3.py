#!/usr/bin/env python3
"""Stores CDR messages (JSON lines from write_mcap.mjs: topic, type, time in
ns, base64 data, serialized by npm's @foxglove/rosmsg2-serialization) in a
rosbag2 folder as ROS 2 Humble records it: metadata.yaml and one sqlite3
file with its schema, topics and messages tables (Python's sqlite3).
--split N stores the messages in N files, as `ros2 bag record
--max-bag-size` does. --wal leaves each file as a recorder killed while
writing does: in WAL mode, its messages still in FILE-wal (with FILE-shm)."""
import argparse
import base64
import json
import os
import sqlite3
import sys

SCHEMA = """
CREATE TABLE schema(schema_version INTEGER PRIMARY KEY, ros_distro TEXT NOT NULL);
CREATE TABLE metadata(id INTEGER PRIMARY KEY, metadata_version INTEGER NOT NULL, metadata TEXT NOT NULL);
CREATE TABLE topics(id INTEGER PRIMARY KEY, name TEXT NOT NULL, type TEXT NOT NULL,
                    serialization_format TEXT NOT NULL, offered_qos_profiles TEXT NOT NULL);
CREATE TABLE messages(id INTEGER PRIMARY KEY, topic_id INTEGER NOT NULL, timestamp INTEGER NOT NULL,
                      data BLOB NOT NULL);
CREATE INDEX timestamp_idx ON messages (timestamp ASC);
"""


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("lines")
    parser.add_argument("folder")
    parser.add_argument("--split", type=int, default=1)
    parser.add_argument("--wal", action="store_true")
    args = parser.parse_args()
    messages = [json.loads(line) for line in open(args.lines)]
    os.makedirs(args.folder)
    per_file = (len(messages) + args.split - 1) // args.split
    names = []
    open_files = []
    for part in range(args.split):
        name = "run_%d.db3" % part
        names.append(name)
        db = sqlite3.connect(os.path.join(args.folder, name))
        if args.wal:
            db.execute("PRAGMA journal_mode=WAL")
            db.execute("PRAGMA wal_autocheckpoint=0")
        db.executescript(SCHEMA)
        db.execute("INSERT INTO schema VALUES (3, 'humble')")
        topics = {}
        for m in messages[part * per_file:(part + 1) * per_file]:
            if m["topic"] not in topics:
                topics[m["topic"]] = len(topics) + 1
                db.execute("INSERT INTO topics VALUES (?, ?, ?, 'cdr', '')",
                           (topics[m["topic"]], m["topic"], m["type"]))
            db.execute("INSERT INTO messages (topic_id, timestamp, data) VALUES (?, ?, ?)",
                       (topics[m["topic"]], int(m["time"]), base64.b64decode(m["data"])))
        db.commit()
        if args.wal:
            open_files.append(db)  # never closed: closing would move the log into the file
        else:
            db.close()
    with open(os.path.join(args.folder, "metadata.yaml"), "w") as f:
        f.write("rosbag2_bagfile_information:\n  version: 5\n  storage_identifier: sqlite3\n"
                "  relative_file_paths:\n" + "".join("    - %s\n" % n for n in names) +
                "  message_count: %d\n" % len(messages))
    if args.wal:
        sys.stdout.flush()
        os._exit(0)  # as a killed recorder: no checkpoint, FILE-wal and FILE-shm left
    return 0


if __name__ == "__main__":
    sys.exit(main())
