// Copyright 2026 vehicle_sim contributors
//
// Licensed under the Apache License, Version 2.0 (the "License");
// you may not use this file except in compliance with the License.
// You may obtain a copy of the License at
//
//     http://www.apache.org/licenses/LICENSE-2.0
//
// Unless required by applicable law or agreed to in writing, software
// distributed under the License is distributed on an "AS IS" BASIS,
// WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
// See the License for the specific language governing permissions and
// limitations under the License.


// A Foxglove WebSocket client for test/test_foxglove_live_view.py, written with Foxglove's own
// client library (@foxglove/ws-protocol) and ROS 2 CDR reader and writer
// (@foxglove/rosmsg2-serialization, schemas parsed by @foxglove/rosmsg), so that the server is
// checked by an implementation that is not ours.
//
// Usage: node foxglove_client.js URL SPEED_TOPIC SCENE_TOPIC SERVICE CRUISING_KMH [SUBPROTOCOLS]
// SUBPROTOCOLS: the WebSocket subprotocol names the client offers, comma-separated (default
// foxglove.sdk.v1,foxglove.websocket.v1, as the Foxglove app); the name the server chose is the
// event "connected".
// It subscribes to SPEED_TOPIC (a ROS 2 channel, cdr + ros2msg), SCENE_TOPIC (a
// foxglove.SceneUpdate, protobuf) and /foxglove/transforms (foxglove.FrameTransforms); once the
// speed and the scene are decoded it calls SERVICE (vehicle_msgs/srv/SetFloat) with
// CRUISING_KMH; once the speed has risen by 1 km/h over the speed when the request left (the
// answer may come when the car is already faster), it gets two parameters, sets use_sim_time
// (writable) and then time_step_ms (read-only: refused), and exits 0. Each event is one JSON line
// on stdout; a failure is a line {"event": "error"} and exit code 1.

const { FoxgloveClient } = require('@foxglove/ws-protocol');
const { MessageReader, MessageWriter } = require('@foxglove/rosmsg2-serialization');
const { parse } = require('@foxglove/rosmsg');
const protobuf = require('protobufjs');
const descriptor = require('protobufjs/ext/descriptor');
const WebSocket = require('ws');

const [url, speedTopic, sceneTopic, serviceName, cruisingArg, offerArg] = process.argv.slice(2);
const cruisingKmh = Number(cruisingArg);
const RISE_KMH = 1.0;

function say(event) {
  process.stdout.write(JSON.stringify(event) + '\n');
}

// process.exit drops what a pipe has not taken yet: exit once stdout has written everything.
let finished = false;

function finish(code) {
  if (finished) return;
  finished = true;
  process.stdout.write('', () => process.exit(code));
}

function fail(reason) {
  if (finished) return;
  say({ event: 'error', reason });
  finish(1);
}

// The library leaves the subprotocol to the caller ("a subprotocol which is compatible with the
// ws-protocol spec"): the same protocol is named foxglove.sdk.v1 by foxglove-sdk and the current
// Foxglove app, foxglove.websocket.v1 by the library itself (its README's example), Lichtblick
// and older Foxglove Studio.
const offered = offerArg ? offerArg.split(',')
  : ['foxglove.sdk.v1', FoxgloveClient.SUPPORTED_SUBPROTOCOL];
const ws = new WebSocket(url, offered);
ws.addEventListener('open', () => say({ event: 'connected', protocol: ws.protocol }));
const client = new FoxgloveClient({ ws });
const channels = new Map();        // channel id -> channel
const decoders = new Map();        // subscription id -> (data) -> event
let service = null;
let subscribed = false;
let speedAtCall = null;
let speedBeforeCall = null;
let speeds = 0;
let lastSpeed = null;
let sawScene = false;
let called = false;
let risen = false;

function protobufDecoder(channel) {
  const set = descriptor.FileDescriptorSet.decode(Buffer.from(channel.schema, 'base64'));
  const type = protobuf.Root.fromDescriptor(set).lookupType(channel.schemaName);
  return (data) => type.toObject(type.decode(data), { longs: Number, defaults: true });
}

function ros2Decoder(schema) {
  const reader = new MessageReader(parse(schema, { ros2: true }));
  return (data) => reader.readMessage(data);
}

function maybeSubscribe() {
  if (subscribed) return;
  const byTopic = new Map([...channels.values()].map((c) => [c.topic, c]));
  const speed = byTopic.get(speedTopic);
  const scene = byTopic.get(sceneTopic);
  if (!speed || !scene || !service) return;
  subscribed = true;
  say({ event: 'channels', speed: { encoding: speed.encoding, schemaName: speed.schemaName,
    schemaEncoding: speed.schemaEncoding }, scene: { encoding: scene.encoding,
    schemaName: scene.schemaName, schemaEncoding: scene.schemaEncoding } });
  const decodeSpeed = ros2Decoder(speed.schema);
  decoders.set(client.subscribe(speed.id), (data) => {
    lastSpeed = decodeSpeed(data).data;
    speeds += 1;
    if (speeds <= 5) say({ event: 'speed', value: lastSpeed });   // the first ones only
    checkRisen();
  });
  const transforms = byTopic.get('/foxglove/transforms');
  if (transforms) {
    const decodeTransforms = protobufDecoder(transforms);
    let sawTransforms = false;
    decoders.set(client.subscribe(transforms.id), (data) => {
      if (sawTransforms) return;
      sawTransforms = true;
      say({ event: 'transforms', transforms: decodeTransforms(data).transforms.map((t) => ({
        parent: t.parent_frame_id ?? t.parentFrameId, child: t.child_frame_id ?? t.childFrameId,
        translation: t.translation, rotation: t.rotation })) });
    });
  }
  const decodeScene = protobufDecoder(scene);
  decoders.set(client.subscribe(scene.id), (data) => {
    if (sawScene) return;
    sawScene = true;
    const update = decodeScene(data);
    say({ event: 'scene', entities: update.entities.map((e) => ({
      id: e.id, frame_id: e.frame_id ?? e.frameId, cubes: e.cubes, cylinders: e.cylinders,
      spheres: e.spheres,
      // lines and triangles in short: their type, size, colour and first points
      lines: (e.lines || []).map((l) => ({ type: l.type, thickness: l.thickness,
        color: l.color, count: l.points.length, first: l.points.slice(0, 2) })),
      triangles: (e.triangles || []).map((t) => ({ color: t.color, points: t.points.length,
        indices: t.indices.length })) })) });
  });
}

function checkRisen() {
  if (speedAtCall === null || risen || lastSpeed < speedAtCall + RISE_KMH) return;
  risen = true;
  say({ event: 'risen', from: speedAtCall, to: lastSpeed });
  // Then the parameter capability: read two, set the writable one, try a read-only one.
  client.getParameters(['time_step_ms', 'cmd_vel_timeout_s'], 'get');
}

function maybeCall() {
  if (called || lastSpeed === null || !sawScene) return;
  called = true;
  const request = new MessageWriter(parse(service.request.schema, { ros2: true }));
  const data = request.writeMessage({ value: cruisingKmh });
  say({ event: 'call', service: service.name, type: service.type,
    requestSchemaName: service.request.schemaName, value: cruisingKmh });
  // The speed when the request leaves: the car is at rest until the node runs it.
  speedBeforeCall = lastSpeed;
  client.sendServiceCallRequest({ serviceId: service.id, callId: 1, encoding: 'cdr', data });
}

client.on('error', (error) => fail(`connection: ${error && error.message}`));
client.on('close', () => fail('the server closed the connection'));
client.on('advertise', (list) => {
  for (const channel of list) channels.set(channel.id, channel);
  maybeSubscribe();
});
client.on('advertiseServices', (list) => {
  for (const s of list) if (s.name === serviceName) service = s;
  maybeSubscribe();
});
client.on('message', ({ subscriptionId, data }) => {
  const decode = decoders.get(subscriptionId);
  if (decode) decode(new Uint8Array(data.buffer, data.byteOffset, data.byteLength));
  maybeCall();
});
client.on('serviceCallResponse', (response) => {
  const reader = ros2Decoder(service.response.schema);
  const decoded = reader(new Uint8Array(response.data.buffer, response.data.byteOffset,
    response.data.byteLength));
  say({ event: 'response', encoding: response.encoding, success: decoded.success });
  if (!decoded.success) fail('the service refused the value');
  speedAtCall = speedBeforeCall;
  checkRisen();
});
client.on('parameterValues', ({ parameters, id }) => {
  say({ event: 'parameters', id, parameters });
  if (id === 'get') {
    client.setParameters([{ name: 'use_sim_time', value: true }], 'set');
  } else if (id === 'set') {
    client.setParameters([{ name: 'time_step_ms', value: 20 }], 'refused');
  } else if (id === 'refused') {
    finish(0);
  }
});
client.on('status', (status) => say({ event: 'status', level: status.level,
  message: status.message }));
client.on('serviceCallFailure', (failure) => fail(`service call failed: ${failure.message}`));
setTimeout(() => fail(`timed out; speed ${lastSpeed}, scene ${sawScene}, called ${called}`),
  60000);
