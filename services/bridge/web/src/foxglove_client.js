// A minimal Foxglove WebSocket protocol v1 client (github.com/foxglove/ws-protocol docs/spec.md): only what a live
// viewer of the bridge needs. It subscribes to every channel whose message encoding is JSON (the bridge's derived,
// well-known channels); CDR channels carry the raw pipeline messages, which this page has no decoder for.
// Written here rather than pulled from a library so the bundle stays small and the page works offline.

export const SUBPROTOCOL = 'foxglove.websocket.v1';
const OP_MESSAGE_DATA = 0x01;

export class FoxgloveClient {
  // handlers: onState({state, detail}), onMessage(channel, payloadObject, receiveTimeNs), onChannels(list),
  // onServerStatus({level, message}).
  constructor(url, handlers) {
    this.url = url;
    this.handlers = handlers;
    this.channels = new Map(); // channel id -> channel (advertised, JSON only)
    this.subscriptions = new Map(); // subscription id -> channel
    this.byChannel = new Map(); // channel id -> subscription id
    this.nextSubscriptionId = 1;
    this.backoffMs = 500;
    this.socket = null;
    this.retryTimer = null;
    this.decoder = new TextDecoder();
    this.stats = { messages: 0, bytes: 0, undecodable: 0, connects: 0 };
    this.serverName = '';
  }

  start() {
    this.connect();
  }

  connect() {
    this.retryTimer = null;
    this.setState('connecting', this.url);
    let socket;
    try {
      socket = new WebSocket(this.url, [SUBPROTOCOL]);
    } catch (err) {
      this.scheduleReconnect(String(err));
      return;
    }
    socket.binaryType = 'arraybuffer';
    this.socket = socket;
    socket.onopen = () => {
      // A fresh connection: the server advertises its channels again, subscription ids start over.
      this.channels.clear();
      this.subscriptions.clear();
      this.byChannel.clear();
      this.backoffMs = 500;
      this.stats.connects += 1;
      this.setState('connected', this.url);
      this.handlers.onChannels?.([...this.channels.values()]);
    };
    socket.onmessage = (event) => this.onSocketMessage(event.data);
    socket.onerror = () => {}; // onclose follows and reports it
    socket.onclose = (event) => {
      if (this.socket !== socket) return;
      this.socket = null;
      this.scheduleReconnect(event.reason || `closed (code ${event.code})`);
    };
  }

  scheduleReconnect(reason) {
    if (this.retryTimer) return;
    const delay = this.backoffMs;
    // Exponential backoff up to 10 s: a restarting bridge is not hammered, a quick restart is caught quickly.
    this.backoffMs = Math.min(10000, this.backoffMs * 2);
    this.setState('disconnected', `${reason}; retrying in ${(delay / 1000).toFixed(1)} s`);
    this.retryTimer = setTimeout(() => this.connect(), delay);
  }

  setState(state, detail) {
    this.state = state;
    this.handlers.onState?.({ state, detail, serverName: this.serverName });
  }

  send(obj) {
    if (this.socket && this.socket.readyState === WebSocket.OPEN) this.socket.send(JSON.stringify(obj));
  }

  onSocketMessage(data) {
    if (typeof data === 'string') {
      let msg;
      try {
        msg = JSON.parse(data);
      } catch {
        return; // not JSON: nothing this client can act on
      }
      this.onText(msg);
    } else if (data instanceof ArrayBuffer) {
      this.onBinary(data);
    }
  }

  onText(msg) {
    switch (msg.op) {
      case 'serverInfo':
        this.serverName = msg.name || '';
        this.setState('connected', this.url);
        break;
      case 'advertise':
        this.onAdvertise(msg.channels || []);
        break;
      case 'unadvertise':
        for (const id of msg.channelIds || []) {
          const sub = this.byChannel.get(id);
          if (sub !== undefined) this.subscriptions.delete(sub);
          this.byChannel.delete(id);
          this.channels.delete(id);
        }
        this.handlers.onChannels?.([...this.channels.values()]);
        break;
      case 'status':
        this.handlers.onServerStatus?.({ level: msg.level, message: msg.message });
        break;
      default:
        break; // other ops (parameters, services...) are not used by this view
    }
  }

  onAdvertise(channels) {
    const subscriptions = [];
    for (const ch of channels) {
      if (ch.encoding !== 'json' || this.byChannel.has(ch.id)) continue;
      const id = this.nextSubscriptionId++;
      this.channels.set(ch.id, ch);
      this.subscriptions.set(id, ch);
      this.byChannel.set(ch.id, id);
      subscriptions.push({ id, channelId: ch.id });
    }
    if (subscriptions.length > 0) this.send({ op: 'subscribe', subscriptions });
    this.handlers.onChannels?.([...this.channels.values()]);
  }

  onBinary(buffer) {
    // Message Data: u8 opcode, u32 LE subscription id, u64 LE receive time [ns], payload.
    if (buffer.byteLength < 13) return;
    const view = new DataView(buffer);
    if (view.getUint8(0) !== OP_MESSAGE_DATA) return;
    const channel = this.subscriptions.get(view.getUint32(1, true));
    if (!channel) return; // a message in flight for a channel unadvertised meanwhile
    const receiveTimeNs = view.getBigUint64(5, true);
    this.stats.messages += 1;
    this.stats.bytes += buffer.byteLength;
    let payload;
    try {
      payload = JSON.parse(this.decoder.decode(new Uint8Array(buffer, 13)));
    } catch {
      this.stats.undecodable += 1;
      return;
    }
    this.handlers.onMessage?.(channel, payload, receiveTimeNs);
  }
}

// The bridge's own host serves the page, so the socket is on the same host:port; `?ws=` overrides it for development.
export function socketUrl(location) {
  const override = new URLSearchParams(location.search).get('ws');
  if (override) return override;
  const scheme = location.protocol === 'https:' ? 'wss' : 'ws';
  return `${scheme}://${location.host}/`;
}
