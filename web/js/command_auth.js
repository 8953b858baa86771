// Signs the page's operator commands as the server verifies them (docs/lcm.md
// "Operator command authentication", server/include/fireswarm/server/command_auth.hpp):
// HMAC-SHA256 by WebCrypto under the operator's 256-bit key over the canonical
// bytes of the command and its credentials. The key never leaves the page: it is
// kept in sessionStorage and only the tag is sent, in the body's `auth` member.

const TAG = 'fireswarm-cmd-v1';
const KEY_HEX = /^[0-9a-fA-F]{64}$/;
const OPERATOR_ID = /^[A-Za-z0-9_-][A-Za-z0-9_.-]{0,63}$/;

/** operator_command_t's command constants, by the API's `kind`. */
export const COMMAND_CODES = {
  start: 1, abort: 2, return_all: 3, investigate: 4, retask: 5, hold: 6, resume: 7, return: 8,
  land: 9, hold_all: 10, resume_all: 11,
};

function hex(bytes) {
  return [...bytes].map((b) => b.toString(16).padStart(2, '0')).join('');
}

/** Why `operator` or `keyHex` cannot sign (a message), or '' when both are fine. */
export function credentialsProblem(operator, keyHex) {
  if (!OPERATOR_ID.test(operator)) return 'operator: 1..64 of A-Z a-z 0-9 _ . - (as its key file is named)';
  if (!KEY_HEX.test(keyHex)) return 'key: the 64 hex digits of the operator\'s .key file';
  return '';
}

/**
 * The bytes the MAC covers for an API command `body` ({kind, vehicle?, lat?,
 * lon?, radius_m?, reason?}) by `operator` at `utime` (µs, a Number) with
 * `nonce` (a BigInt, 64 bits). Absent fields count as 0 (and '').
 */
export function macInput(body, operator, utime, nonce) {
  const encoder = new TextEncoder();
  const tag = encoder.encode(TAG);
  const who = encoder.encode(operator);
  const reason = encoder.encode(body.reason ?? '');
  const bytes = new Uint8Array(tag.length + 1 + who.length + 8 + 8 + 1 + 2 + 3 * 8 + 2 + reason.length);
  const view = new DataView(bytes.buffer); // big-endian unless told otherwise
  let at = 0;
  bytes.set(tag, at);
  at += tag.length;
  view.setUint8(at, who.length);
  bytes.set(who, at + 1);
  at += 1 + who.length;
  view.setBigInt64(at, BigInt(utime));
  view.setBigUint64(at + 8, BigInt.asUintN(64, nonce));
  at += 16;
  view.setInt8(at, COMMAND_CODES[body.kind] ?? 0);
  view.setInt16(at + 1, body.vehicle ?? 0);
  at += 3;
  for (const value of [body.lat ?? 0, body.lon ?? 0, body.radius_m ?? 0]) {
    view.setFloat64(at, value + 0); // -0 is sent as 0 in JSON: sign 0
    at += 8;
  }
  view.setUint16(at, reason.length);
  bytes.set(reason, at + 2);
  return bytes;
}

/**
 * `body` with its `auth` member: {operator, utime, nonce: 16 hex digits, mac: 64
 * hex digits}, signed with `keyHex` at `utime` (the server's clock, µs) and a
 * random nonce.
 */
export async function signCommand(body, operator, keyHex, utime) {
  const raw = new Uint8Array(keyHex.match(/../g).map((pair) => parseInt(pair, 16)));
  const key = await crypto.subtle.importKey('raw', raw, { name: 'HMAC', hash: 'SHA-256' }, false, ['sign']);
  const nonceBytes = crypto.getRandomValues(new Uint8Array(8));
  const nonce = new DataView(nonceBytes.buffer).getBigUint64(0);
  const when = Math.round(utime);
  const mac = new Uint8Array(await crypto.subtle.sign('HMAC', key, macInput(body, operator, when, nonce)));
  return { ...body, auth: { operator, utime: when, nonce: hex(nonceBytes), mac: hex(mac) } };
}
