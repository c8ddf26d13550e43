// Writes the ROS 2 fixtures with implementations that are not imucal's: Foxglove's MCAP writer
// (@mcap/core, the format's reference), its CDR writer (@foxglove/cdr), zstd (@bokuweb/zstd-wasm) and LZ4
// frames (lz4js). Run once; the files are committed (CI needs no network):
//   npm install && node make_fixtures.mjs
// Source: ../ros1/imu.csv and mag.csv (SI, FRD), as the ROS 1 fixtures. Each sample becomes a
// sensor_msgs/msg/Imu on /imu/data (FLU: y and z negated) stamped 1700000000 s + t, every third a
// sensor_msgs/msg/MagneticField on /mag (tesla), in plain little-endian CDR as rmw writes it.
//   imu.mcap (chunks uncompressed), imu_zstd.mcap, imu_lz4.mcap; two_imus.mcap (a copy on /imu2/data_raw);
//   xcdr2.mcap: the IMU in XCDR2 (encapsulation 0x0007), which the reader must refuse by name.
//   imu_cdr_be.mcap: the IMU in big-endian CDR.
// ../../fuzz/corpus/fuzz_mcap/: the first few samples, uncompressed, zstd and lz4: the fuzzer's seeds.
// imu.db3: the same messages in rosbag2's sqlite3 storage (its Humble schema), the CDR from @foxglove/cdr
// and the file from the sqlite3 tool (Debian sqlite3). sqlite_folder/: a rosbag2 folder (metadata.yaml)
// split in two .db3 files holding the first 300 samples; mcap_folder/: one holding imu_zstd.mcap's copy.
// ../../fuzz/corpus/fuzz_rosbag2_db3/seed.db3: the first few samples, the fuzzer's seed.
import fs from "node:fs";
import { execFileSync } from "node:child_process";
import { McapWriter } from "@mcap/core";
import { CdrWriter } from "@foxglove/cdr";
import { init as zstdInit, compress as zstdCompress } from "@bokuweb/zstd-wasm";
import lz4 from "lz4js";

const EPOCH = 1700000000n;
const IMU_DEF = fs.readFileSync(new URL("./Imu.msg", import.meta.url), "utf8");
const MAG_DEF = fs.readFileSync(new URL("./MagneticField.msg", import.meta.url), "utf8");

function rows(path) {
  const lines = fs.readFileSync(new URL(path, import.meta.url), "utf8").trim().split("\n").slice(1);
  return lines.map((l) => l.split(",").map(Number));
}

function stampNs(t) {
  return EPOCH * 1000000000n + BigInt(Math.round(t * 1e9));
}

function header(w, ns) {
  w.int32(Number(ns / 1000000000n));
  w.uint32(Number(ns % 1000000000n));
  w.string("imu_link");
}

function imuCdr([t, ax, ay, az, gx, gy, gz], kind) {
  const w = new CdrWriter({ kind });
  header(w, stampNs(t));
  for (const v of [0, 0, 0, 1]) w.float64(v);
  for (let i = 0; i < 9; ++i) w.float64(i === 0 ? -1 : 0); // no orientation (REP 145)
  for (const v of [gx, -gy, -gz]) w.float64(v);
  for (let i = 0; i < 9; ++i) w.float64(0);
  for (const v of [ax, -ay, -az]) w.float64(v);
  for (let i = 0; i < 9; ++i) w.float64(0);
  return w.data;
}

function magCdr([t, mx, my, mz]) {
  const w = new CdrWriter({ kind: 1 });
  header(w, stampNs(t));
  for (const v of [mx * 1e-6, -my * 1e-6, -mz * 1e-6]) w.float64(v);
  for (let i = 0; i < 9; ++i) w.float64(0);
  return w.data;
}

class FileWritable {
  constructor() { this.parts = []; this.size = 0n; }
  async write(buffer) { this.parts.push(Buffer.from(buffer)); this.size += BigInt(buffer.byteLength); }
  position() { return this.size; }
}

async function write(path, { compression = "", imuKind = 1, extraImu = null, samples = Infinity } = {}) {
  const compressChunk = compression === "zstd"
    ? (data) => ({ compression: "zstd", compressedData: zstdCompress(data, 3) })
    : compression === "lz4"
      ? (data) => ({ compression: "lz4", compressedData: lz4.compress(data) })
      : undefined;
  const out = new FileWritable();
  const writer = new McapWriter({ writable: out, chunkSize: 64 * 1024, compressChunk });
  await writer.start({ profile: "ros2", library: "@mcap/core 2.2.2 (imucal fixtures)" });
  const imuSchema = await writer.registerSchema({ name: "sensor_msgs/msg/Imu", encoding: "ros2msg",
                                                  data: new TextEncoder().encode(IMU_DEF) });
  const magSchema = await writer.registerSchema({ name: "sensor_msgs/msg/MagneticField", encoding: "ros2msg",
                                                  data: new TextEncoder().encode(MAG_DEF) });
  const channel = async (topic, schemaId) =>
    writer.registerChannel({ topic, schemaId, messageEncoding: "cdr", metadata: new Map() });
  const imuChannel = await channel("/imu/data", imuSchema);
  const extraChannel = extraImu ? await channel(extraImu, imuSchema) : null;
  const magChannel = await channel("/mag", magSchema);
  const imu = rows("../ros1/imu.csv").slice(0, samples);
  const mag = rows("../ros1/mag.csv");
  let sequence = 0;
  for (let i = 0; i < imu.length; ++i) {
    const ns = stampNs(imu[i][0]);
    const data = imuCdr(imu[i], imuKind);
    await writer.addMessage({ channelId: imuChannel, sequence: sequence++, logTime: ns, publishTime: ns, data });
    if (extraChannel !== null)
      await writer.addMessage({ channelId: extraChannel, sequence: sequence++, logTime: ns, publishTime: ns, data });
    if (i % 3 === 0) {
      await writer.addMessage({ channelId: magChannel, sequence: sequence++, logTime: ns, publishTime: ns,
                                data: magCdr(mag[i / 3]) });
    }
  }
  await writer.end();
  fs.writeFileSync(new URL(path, import.meta.url), Buffer.concat(out.parts));
}

await zstdInit();
await write("imu.mcap");
await write("imu_zstd.mcap", { compression: "zstd" });
await write("imu_lz4.mcap", { compression: "lz4" });
await write("two_imus.mcap", { compression: "zstd", extraImu: "/imu2/data_raw" });
await write("xcdr2.mcap", { compression: "zstd", imuKind: 7 });
await write("imu_cdr_be.mcap", { compression: "zstd", imuKind: 0 });
fs.mkdirSync(new URL("../../fuzz/corpus/fuzz_mcap/", import.meta.url), { recursive: true });
for (const compression of ["", "zstd", "lz4"])
  await write(`../../fuzz/corpus/fuzz_mcap/seed_${compression || "none"}.mcap`,
              { compression, extraImu: "/imu2/data_raw", samples: 7 });

const QOS = "- history: 3\n  depth: 0\n  reliability: 1\n  durability: 2\n";

function db3(path, imu, mag, firstId = 1) {
  const file = new URL(path, import.meta.url).pathname;
  fs.rmSync(file, { force: true });
  const hex = (bytes) => Buffer.from(bytes).toString("hex");
  const sql = [
    "PRAGMA journal_mode=OFF;",
    "CREATE TABLE schema(schema_version INTEGER PRIMARY KEY,ros_distro TEXT NOT NULL);",
    "INSERT INTO schema VALUES(3,'humble');",
    "CREATE TABLE metadata(id INTEGER PRIMARY KEY,metadata_version INTEGER NOT NULL,metadata TEXT NOT NULL);",
    "CREATE TABLE topics(id INTEGER PRIMARY KEY,name TEXT NOT NULL,type TEXT NOT NULL," +
      "serialization_format TEXT NOT NULL,offered_qos_profiles TEXT NOT NULL);",
    "CREATE TABLE messages(id INTEGER PRIMARY KEY,topic_id INTEGER NOT NULL,timestamp INTEGER NOT NULL,data BLOB NOT NULL);",
    "CREATE INDEX timestamp_idx ON messages (timestamp ASC);",
    `INSERT INTO topics VALUES(1,'/imu/data','sensor_msgs/msg/Imu','cdr','${QOS}');`,
    `INSERT INTO topics VALUES(2,'/mag','sensor_msgs/msg/MagneticField','cdr','${QOS}');`,
    "BEGIN;",
  ];
  let id = firstId;
  for (let i = 0; i < imu.length; ++i) {
    const ns = stampNs(imu[i][0]);
    sql.push(`INSERT INTO messages VALUES(${id++},1,${ns},X'${hex(imuCdr(imu[i], 1))}');`);
    if (mag[i] !== undefined) sql.push(`INSERT INTO messages VALUES(${id++},2,${ns},X'${hex(magCdr(mag[i]))}');`);
  }
  sql.push("COMMIT;");
  execFileSync("sqlite3", [file], { input: sql.join("\n") });
}

function metadata(folder, storage, files, count) {
  const text = [
    "rosbag2_bagfile_information:",
    "  version: 5",
    `  storage_identifier: ${storage}`,
    "  duration:",
    "    nanoseconds: 2990000000",
    "  starting_time:",
    "    nanoseconds_since_epoch: 1700000000000000000",
    `  message_count: ${count}`,
    "  topics_with_message_count: []",
    "  compression_format: \"\"",
    "  compression_mode: \"\"",
    "  relative_file_paths:",
    ...files.map((f) => `    - ${f}`),
    "",
  ].join("\n");
  fs.writeFileSync(new URL(`${folder}/metadata.yaml`, import.meta.url), text);
}

{
  const imu = rows("../ros1/imu.csv");
  const magRows = rows("../ros1/mag.csv");
  const magAt = (i) => (i % 3 === 0 ? magRows[i / 3] : undefined);
  db3("imu.db3", imu, imu.map((_, i) => magAt(i)));
  fs.mkdirSync(new URL("sqlite_folder/", import.meta.url), { recursive: true });
  db3("sqlite_folder/rec_0.db3", imu.slice(0, 150), imu.slice(0, 150).map((_, i) => magAt(i)));
  db3("sqlite_folder/rec_1.db3", imu.slice(150, 300), imu.slice(150, 300).map((_, i) => magAt(i + 150)), 1000);
  metadata("sqlite_folder", "sqlite3", ["rec_0.db3", "rec_1.db3"], 400);
  fs.mkdirSync(new URL("mcap_folder/", import.meta.url), { recursive: true });
  fs.copyFileSync(new URL("imu_zstd.mcap", import.meta.url), new URL("mcap_folder/rec_0.mcap", import.meta.url));
  metadata("mcap_folder", "mcap", ["rec_0.mcap"], 1202);
  fs.mkdirSync(new URL("../../fuzz/corpus/fuzz_rosbag2_db3/", import.meta.url), { recursive: true });
  db3("../../fuzz/corpus/fuzz_rosbag2_db3/seed.db3", imu.slice(0, 7), imu.slice(0, 7).map((_, i) => magAt(i)));
}
