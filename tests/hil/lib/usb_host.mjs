// A USB host for the emulated chip's composite device: enumerates it the way
// rp2040js's USBCDC helper does, but binds every CDC ACM port (the helper
// binds only the last data interface, the protocol port), raises DTR on
// each, and holds the device's OUT requests until there is something to send
// (a real host sends nothing when it has nothing to say).
import {
  createSetupPacket,
  DataDirection,
  DescriptorType,
  getDescriptorPacket,
  setDeviceAddressPacket,
  setDeviceConfigurationPacket,
  SetupRecipient,
  SetupType,
} from 'rp2040js';

const CDC_SET_CONTROL_LINE_STATE = 0x22;
const CDC_COMM_CLASS = 2;
const CDC_DATA_CLASS = 10;

/** The CDC ports in a configuration descriptor: [{ comm, in, out }], in interface order. */
export function cdcPorts(descriptors) {
  const ports = [];
  let comm = -1;
  let current = null;
  for (let i = 0; i + 1 < descriptors.length; ) {
    const len = descriptors[i];
    if (len < 2 || i + len > descriptors.length) break;
    const type = descriptors[i + 1];
    if (type === DescriptorType.Interface && len === 9) {
      const number = descriptors[i + 2];
      const cls = descriptors[i + 5];
      current = null;
      if (cls === CDC_COMM_CLASS) comm = number;
      if (cls === CDC_DATA_CLASS && comm >= 0) {
        current = { comm, in: -1, out: -1 };
        ports.push(current);
      }
    }
    if (current && type === DescriptorType.Endpoint && len === 7 && (descriptors[i + 3] & 3) === 2) {
      const address = descriptors[i + 2];
      if (address & 0x80) current.in = address & 0xf;
      else current.out = address & 0xf;
    }
    i += len;
  }
  return ports;
}

/** The class of every interface in a configuration descriptor (2 CDC, 10 CDC data, 8 mass storage, 0xff vendor). */
export function interfaceClasses(descriptors) {
  const out = [];
  for (let i = 0; i + 1 < descriptors.length && descriptors[i] >= 2; i += descriptors[i]) {
    if (descriptors[i + 1] === DescriptorType.Interface && descriptors[i] === 9) out.push(descriptors[i + 5]);
  }
  return out;
}

/** One CDC port on the host side: write() to the device, onData from it. */
export class CdcPort {
  constructor(host, index) {
    this.host = host;
    this.index = index;
    this.tx = [];
    this.pendingRead = 0; // size the device asked for, 0: none
    this.onData = null;
  }
  write(bytes) {
    for (const b of bytes) this.tx.push(b);
    this.host.flush(this);
  }
  setDtr(on) {
    this.host.controlLineState(this, on);
  }
}

export class UsbHost {
  constructor(usb) {
    this.usb = usb;
    this.ports = [];
    this.connected = false;
    this.onConnected = null;
    this.onPorts = null;
    this.setupQueue = [];
    this.descriptorsSize = null;
    this.descriptors = [];
    this.byIn = new Map();
    this.byOut = new Map();
    usb.onUSBEnabled = () => usb.resetDevice();
    usb.onResetReceived = () => usb.sendSetupPacket(setDeviceAddressPacket(1));
    usb.onEndpointWrite = (endpoint, buffer) => this.endpointWrite(endpoint, buffer);
    usb.onEndpointRead = (endpoint, size) => {
      const port = this.byOut.get(endpoint);
      if (!port) return;
      port.pendingRead = size;
      this.flush(port);
    };
  }

  endpointWrite(endpoint, buffer) {
    if (endpoint === 0 && buffer.length === 0) {
      // Status stage of a control transfer: the next request may go.
      if (this.descriptorsSize == null) {
        this.usb.sendSetupPacket(getDescriptorPacket(DescriptorType.Configration, 9));
      } else if (this.setupQueue.length > 0) {
        this.usb.sendSetupPacket(this.setupQueue.shift());
      } else if (!this.connected && this.ports.length > 0 && this.configured) {
        this.connected = true;
        this.onConnected?.();
      }
      return;
    }
    if (endpoint === 0) {
      if (buffer.length === 9 && buffer[1] === DescriptorType.Configration && this.descriptorsSize == null) {
        this.descriptorsSize = (buffer[3] << 8) | buffer[2];
        this.usb.sendSetupPacket(getDescriptorPacket(DescriptorType.Configration, this.descriptorsSize));
        return;
      }
      if (this.descriptorsSize != null && this.descriptors.length < this.descriptorsSize) {
        this.descriptors.push(...buffer);
        if (this.descriptors.length >= this.descriptorsSize) {
          this.interfaceClasses = interfaceClasses(this.descriptors);
          for (const p of cdcPorts(this.descriptors)) {
            const port = new CdcPort(this, this.ports.length);
            Object.assign(port, p);
            this.ports.push(port);
            this.byIn.set(p.in, port);
            this.byOut.set(p.out, port);
          }
          this.configured = true;
          this.onPorts?.(this.ports); // bound before the device can send
          for (const port of this.ports) this.setupQueue.push(this.lineStatePacket(port, true));
          this.usb.sendSetupPacket(setDeviceConfigurationPacket(1));
        }
      }
      return;
    }
    const port = this.byIn.get(endpoint);
    if (port) port.onData?.(buffer);
  }

  lineStatePacket(port, dtr) {
    return createSetupPacket({
      dataDirection: DataDirection.HostToDevice,
      type: SetupType.Class,
      recipient: SetupRecipient.Interface,
      bRequest: CDC_SET_CONTROL_LINE_STATE,
      wValue: dtr ? 3 : 0, // DTR | RTS
      wIndex: port.comm,
      wLength: 0,
    });
  }

  controlLineState(port, dtr) {
    const packet = this.lineStatePacket(port, dtr);
    if (this.connected && this.setupQueue.length === 0) this.usb.sendSetupPacket(packet);
    else this.setupQueue.push(packet);
  }

  flush(port) {
    if (port.pendingRead === 0 || port.tx.length === 0) return;
    const n = Math.min(port.pendingRead, port.tx.length);
    const chunk = new Uint8Array(port.tx.splice(0, n));
    port.pendingRead = 0;
    this.usb.endpointReadDone(port.out, chunk);
  }
}
