# Copyright 2026 vehicle_sim contributors
#
# Licensed under the Apache License, Version 2.0 (the "License");
# you may not use this file except in compliance with the License.
# You may obtain a copy of the License at
#
#     http://www.apache.org/licenses/LICENSE-2.0
#
# Unless required by applicable law or agreed to in writing, software
# distributed under the License is distributed on an "AS IS" BASIS,
# WITHOUT WARRANTIES OR CONDITIONS OF ANY KIND, either express or implied.
# See the License for the specific language governing permissions and
# limitations under the License.

"""
Environment handling of the embedded transport: ROS_DOMAIN_ID, discovery range, the Cyclone domain.

The discovery range is read like rcl (Jazzy ``init.c``, ``discovery_options.c``) and turned into
the Cyclone configuration fragment that rmw_cyclonedds (Jazzy ``rmw_node.cpp``,
``check_create_domain``) builds, followed by the user's ``CYCLONEDDS_URI`` so that the user's
explicit settings win:

* ``LOCALHOST`` (or ``ROS_LOCALHOST_ONLY=1``, which wins over the range and drops the static
  peers): no multicast, ``ParticipantIndex auto`` (at most 32), peer ``localhost`` plus
  ``ROS_STATIC_PEERS``.
* ``OFF``: no multicast, ``ParticipantIndex none`` and a per-process discovery ``Tag``; static
  peers are ignored.
* ``SUBNET`` (the default): ``ParticipantIndex auto`` (at most 32) plus ``ROS_STATIC_PEERS`` as
  peers; multicast discovery stays on.
* ``SYSTEM_DEFAULT``: nothing; static peers are ignored.

Additions of our own come first (so that the user's URI can still override them):

* LOCALHOST pins the loopback interface, to keep our traffic on 127.0.0.1, but only when the
  user's ``CYCLONEDDS_URI`` selects no interface itself (Cyclone refuses an interface selected
  twice, and rmw pins none, so a user URI selecting ``lo`` or ``127.0.0.1`` must work as is).
* LOCALHOST announces the participant every ``Discovery/SPDPInterval`` 1 s (Cyclone's default is
  30 s) to its unicast peers: without multicast, a peer that discovers by multicast only never
  reaches us, and learns of us from our announcements alone. ROS 2 Humble's Fast DDS with
  ``ROS_LOCALHOST_ONLY=1`` (Humble's default RMW) is such a peer: measured, its ``ros2 node list``
  never listed a node started before it (not after 60 s with the daemon); with 1 s it does within
  its usual spin time. The cost is one small datagram per second to each of the 33 localhost
  ports (participant indices 0..32).
* ``Internal/WriterLingerDuration`` 0 s: Cyclone keeps a deleted reliable writer alive up to that
  long (default 1 s) while samples are unacknowledged, e.g. a reply to a client that died, and a
  participant deletes its writers one after the other; a node must leave the graph at once.

:func:`create_domain` makes any error Cyclone raises while creating the domain one line that
names the environment variables involved.
"""

import os
import re
import sys
import tempfile
from typing import List, Mapping, Optional
from xml.etree import ElementTree
from xml.sax.saxutils import quoteattr

from vehicle_sim.transport.errors import TransportError

RANGES = ('SUBNET', 'LOCALHOST', 'OFF', 'SYSTEM_DEFAULT')
DEFAULT_RANGE = 'SUBNET'
MAX_DOMAIN_ID = 232
MAX_AUTO_PARTICIPANT_INDEX = 32
LOOPBACK_ADDRESS = '127.0.0.1'
# How often a LOCALHOST participant announces itself to its unicast peers (see the module doc).
LOCALHOST_SPDP_INTERVAL = '1 s'
# The environment variables that shape the domain, named in its error messages.
ENV_VARS = ('ROS_DOMAIN_ID', 'ROS_AUTOMATIC_DISCOVERY_RANGE', 'ROS_LOCALHOST_ONLY',
            'ROS_STATIC_PEERS', 'CYCLONEDDS_URI')


def domain_id(env: Optional[Mapping[str, str]] = None) -> int:
    """
    Return ``ROS_DOMAIN_ID`` (default 0).

    :raises TransportError: when it is not an integer in 0..232.
    """
    env = os.environ if env is None else env
    text = env.get('ROS_DOMAIN_ID', '').strip()
    if not text:
        return 0
    try:
        value = int(text)
    except ValueError:
        raise TransportError(f'ROS_DOMAIN_ID={text!r} is not an integer') from None
    if not 0 <= value <= MAX_DOMAIN_ID:
        raise TransportError(f'ROS_DOMAIN_ID={value} outside 0..{MAX_DOMAIN_ID}')
    return value


def localhost_only(env: Optional[Mapping[str, str]] = None) -> bool:
    """Return True when the deprecated ``ROS_LOCALHOST_ONLY=1`` is set (it wins, as in rcl)."""
    env = os.environ if env is None else env
    return env.get('ROS_LOCALHOST_ONLY', '').strip() == '1'


def discovery_range(env: Optional[Mapping[str, str]] = None) -> str:
    """
    Return the discovery range: one of SUBNET, LOCALHOST, OFF, SYSTEM_DEFAULT.

    :raises TransportError: for an unknown ``ROS_AUTOMATIC_DISCOVERY_RANGE``.
    """
    env = os.environ if env is None else env
    if localhost_only(env):
        return 'LOCALHOST'
    text = env.get('ROS_AUTOMATIC_DISCOVERY_RANGE', '').strip().upper()
    if not text:
        return DEFAULT_RANGE
    if text not in RANGES:
        raise TransportError(
            f'ROS_AUTOMATIC_DISCOVERY_RANGE={text!r} unknown; valid: {", ".join(RANGES)}')
    return text


def static_peers(env: Optional[Mapping[str, str]] = None) -> List[str]:
    """
    Return the ``ROS_STATIC_PEERS`` addresses (';'-separated) that rmw uses.

    None with ``ROS_LOCALHOST_ONLY=1`` or the OFF and SYSTEM_DEFAULT ranges (rcl and rmw
    ignore them there).
    """
    env = os.environ if env is None else env
    if localhost_only(env) or discovery_range(env) in ('OFF', 'SYSTEM_DEFAULT'):
        return []
    return [p.strip() for p in env.get('ROS_STATIC_PEERS', '').split(';') if p.strip()]


def rmw_fragment(env: Optional[Mapping[str, str]] = None, pid: Optional[int] = None) -> str:
    """
    Return the fragment rmw_cyclonedds (Jazzy) puts before ``CYCLONEDDS_URI`` ('' for none).

    :param pid: the process id in the OFF range's discovery Tag (default: this process).
    """
    scope = discovery_range(env)
    if scope == 'SYSTEM_DEFAULT':
        return ''
    pid = os.getpid() if pid is None else pid
    body = ''
    if scope in ('LOCALHOST', 'OFF'):
        body += '<General><AllowMulticast>false</AllowMulticast></General>'
    if scope == 'OFF':
        body += ('<Discovery><ParticipantIndex>none</ParticipantIndex>'
                 f'<Tag>ros_discovery_off_{pid}</Tag>')
    else:
        body += ('<Discovery><ParticipantIndex>auto</ParticipantIndex>'
                 f'<MaxAutoParticipantIndex>{MAX_AUTO_PARTICIPANT_INDEX}'
                 '</MaxAutoParticipantIndex>')
        peers = (['localhost'] if scope == 'LOCALHOST' else []) + static_peers(env)
        if peers:
            body += '<Peers>' + ''.join(
                f'<Peer address={quoteattr(p)}/>' for p in peers) + '</Peers>'
    return f'<CycloneDDS><Domain>{body}</Discovery></Domain></CycloneDDS>'


def own_fragment(env: Optional[Mapping[str, str]] = None,
                 domain: Optional[int] = None) -> str:
    """Return our additions (writer linger; LOCALHOST's loopback pin and SPDP interval)."""
    env = os.environ if env is None else env
    domain = domain_id(env) if domain is None else domain
    body = ''
    localhost = discovery_range(env) == 'LOCALHOST'
    if localhost and not user_selects_interface(env.get('CYCLONEDDS_URI', ''), domain):
        body += (f'<General><Interfaces><NetworkInterface address="{LOOPBACK_ADDRESS}"/>'
                 '</Interfaces></General>')
    if localhost:
        body += f'<Discovery><SPDPInterval>{LOCALHOST_SPDP_INTERVAL}</SPDPInterval></Discovery>'
    body += '<Internal><WriterLingerDuration>0 s</WriterLingerDuration></Internal>'
    return f'<CycloneDDS><Domain>{body}</Domain></CycloneDDS>'


def cyclone_config(env: Optional[Mapping[str, str]] = None,
                   domain: Optional[int] = None) -> str:
    """
    Return the configuration handed to ``dds_create_domain``.

    Our fragment, rmw's fragment, then the user's ``CYCLONEDDS_URI`` (later settings win).
    Cyclone reads ``CYCLONEDDS_URI`` itself only when given no configuration, so the user's part
    is appended here, as rmw_cyclonedds does.
    """
    env = os.environ if env is None else env
    parts = [own_fragment(env, domain), rmw_fragment(env), env.get('CYCLONEDDS_URI', '').strip()]
    return ','.join(p for p in parts if p)


# --------------------------------------------------------------------------------------------
# Does the user's CYCLONEDDS_URI select an interface?

# One markup token of an inline XML fragment, to find where the fragment ends (Cyclone reads
# an inline fragment up to the end of its root element, then the next comma-separated item).
_XML_TOKEN = re.compile(
    r'<!--.*?-->|<\?.*?\?>|<!\[CDATA\[.*?\]\]>|<!DOCTYPE[^>]*>'
    r'|<(?P<close>/)?[^>]*?(?P<empty>/)?>', re.S)
# Children of General that select interfaces (the deprecated forms clash with Interfaces too).
_INTERFACE_SETTINGS = ('interfaces', 'networkinterfaceaddress', 'assumemulticastcapable',
                       'prefermulticast')


def _split_uri(uri: str) -> List[Optional[str]]:
    """
    Split a ``CYCLONEDDS_URI`` into the XML text of its items, as Cyclone's config reader does.

    Items are inline XML (starting with '<', up to the end of their root element) or file names
    (up to the next comma, with or without ``file://``). An unreadable file gives None.
    """
    items = []
    pos = 0
    while True:
        while pos < len(uri) and (uri[pos].isspace() or uri[pos] == ','):
            pos += 1
        if pos >= len(uri):
            return items
        if uri[pos] == '<':
            depth, end = 0, len(uri)
            for token in _XML_TOKEN.finditer(uri, pos):
                text = token.group(0)
                if text.startswith(('<!', '<?')):
                    continue
                if token.group('close'):
                    depth -= 1
                elif not token.group('empty'):
                    depth += 1
                if depth <= 0:
                    end = token.end()
                    break
            items.append(uri[pos:end])
            pos = end
        else:
            comma = uri.find(',', pos)
            end = len(uri) if comma < 0 else comma
            items.append(_read_config_file(uri[pos:end].strip()))
            pos = end


def _read_config_file(name: str) -> Optional[str]:
    for path in (name, name[len('file://'):] if name.startswith('file://') else None):
        if path:
            try:
                with open(path, encoding='utf-8') as stream:
                    return stream.read()
            except (OSError, UnicodeDecodeError):
                continue
    return None


def _local(tag) -> str:
    return tag.rsplit('}', 1)[-1].lower() if isinstance(tag, str) else ''


def _applies(domain_element, domain: int) -> bool:
    for key, value in domain_element.attrib.items():
        if _local(key) == 'id':
            value = value.strip().lower()
            return value == 'any' or (value.isdigit() and int(value) == domain)
    return True


def _general_selects(general) -> bool:
    for child in general:
        name = _local(child.tag)
        if name == 'interfaces' and len(child):
            return True
        if name == 'networkinterfaceaddress' and (child.text or '').strip().lower() not in (
                '', 'auto'):
            return True
        if name in _INTERFACE_SETTINGS[2:] and (child.text or '').strip().lower() not in (
                '', 'false'):
            return True
    return False


def _xml_selects_interface(root, domain: int) -> bool:
    tag = _local(root.tag)
    # Inline fragments may leave out the CycloneDDS and Domain elements (implicit top level).
    if tag == 'cyclonedds':
        domains = [c for c in root if _local(c.tag) == 'domain']
    elif tag == 'domain':
        domains = [root]
    elif tag == 'general':
        return _general_selects(root)
    else:
        return False
    return any(_general_selects(g) for d in domains if _applies(d, domain)
               for g in d if _local(g.tag) == 'general')


def user_selects_interface(uri: str, domain: int) -> bool:
    """
    Return True when a ``CYCLONEDDS_URI`` selects network interfaces for ``domain``.

    An item that cannot be read or parsed counts as selecting one: we then add nothing and leave
    the user's configuration to Cyclone, as rmw does.
    """
    for text in _split_uri(uri or ''):
        if text is None:
            return True
        try:
            root = ElementTree.fromstring(text)
        except ElementTree.ParseError:
            return True
        if _xml_selects_interface(root, domain):
            return True
    return False


# --------------------------------------------------------------------------------------------
# The domain

def describe_domain_error(domain: int, reason: str,
                          env: Optional[Mapping[str, str]] = None) -> str:
    """Return the one-line message of a failed domain (or participant) creation."""
    env = os.environ if env is None else env
    settings = ', '.join(f'{name}={env[name]!r}' for name in ENV_VARS if env.get(name))
    reason = ' '.join(reason.split()) or 'unknown error'
    where = (f'check {settings}' if settings else
             f'none of {", ".join(ENV_VARS)} is set')
    return f'Cyclone DDS refused domain {domain}: {reason} ({where})'


def create_domain(domain: Optional[int] = None, env: Optional[Mapping[str, str]] = None):
    """
    Create the Cyclone domain with the configuration of the environment.

    Cyclone reports configuration errors on stderr before it fails; they are captured and put
    into the one-line error instead (and passed on to stderr when the domain is created).

    :raises TransportError: naming Cyclone's reason and the environment variables involved.
    """
    from cyclonedds.core import DDSException
    from cyclonedds.domain import Domain

    env = os.environ if env is None else env
    domain = domain_id(env) if domain is None else domain
    config = cyclone_config(env, domain)
    with _StderrCapture() as captured:
        try:
            return Domain(domain, config)
        except DDSException as exc:
            failure = exc
            captured.pass_on = False
    reason = '; '.join(_cyclone_lines(captured.text)) or str(failure)
    raise TransportError(describe_domain_error(domain, reason, env))


# Cyclone's log lines start with a timestamp, the domain id and the thread name.
_CYCLONE_PREFIX = re.compile(r'^\s*\d+\.\d+\s+\[\d*\]\s+[^:]*:\s*')


def _cyclone_lines(text: str) -> List[str]:
    return [_CYCLONE_PREFIX.sub('', line).strip() for line in text.splitlines() if line.strip()]


class _StderrCapture:
    """
    Redirect file descriptor 2 (where Cyclone's C code logs) to a temporary file.

    Process-wide while it lasts (domain creation, once per domain): what other threads write to
    stderr meanwhile is passed on afterwards, or, when the domain is refused, replaced by the
    one-line error.
    """

    def __enter__(self):
        self.text = ''
        self.pass_on = True
        self._file = None
        try:
            sys.stderr.flush()
            self._file = tempfile.TemporaryFile()
            self._saved = os.dup(2)
            os.dup2(self._file.fileno(), 2)
        except (OSError, ValueError, AttributeError):
            self._file = None   # no usable fd 2 (embedded interpreter): do not capture
        return self

    def __exit__(self, *exc):
        if self._file is None:
            return False
        os.dup2(self._saved, 2)
        os.close(self._saved)
        self._file.seek(0)
        self.text = self._file.read().decode('utf-8', 'replace')
        self._file.close()
        if self.pass_on and self.text:
            sys.stderr.write(self.text)   # e.g. warnings of a domain that was created
        return False
