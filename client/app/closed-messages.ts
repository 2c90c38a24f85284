// What the page says when a session ends: a title per ending reason (the SDK's closed reason: a server bye, a refusal
// code, 'unreachable', …) and whether trying the same join again can help. Pure data: no DOM.

/** How the page presents one ending. */
export interface ClosedMessage {
  title: string;
  /** A sentence added under the server's own words. */
  hint: string;
  /** Whether "Try again" (the same join) is worth offering; "Back to rooms" is always offered. */
  retry: boolean;
}

const MESSAGES: Readonly<Record<string, ClosedMessage>> = {
  'server-shutdown': { title: 'The server shut down', hint: 'Try again once it is back, or pick another room.', retry: true },
  'room-closed': { title: 'Room closed', hint: 'An operator closed this room.', retry: false },
  kicked: { title: 'You were removed from the room', hint: 'An operator removed you from this room.', retry: false },
  'room-full': { title: 'The room is full', hint: 'Wait for a player to leave, or pick another room.', retry: true },
  'server-full': { title: 'The server is full', hint: 'Wait a little, or try another server.', retry: true },
  'room-not-found': { title: 'No such room', hint: 'The room may have closed: pick one from the list.', retry: false },
  'version-mismatch': { title: 'This page is out of date', hint: 'The server speaks another protocol version: reload to get the matching page.', retry: true },
  replaced: { title: 'Playing in another tab', hint: 'Another connection took over this player.', retry: false },
  'seat-refused': { title: 'No seat for you', hint: 'This server admits players with a seat only.', retry: false },
  'seat-required': { title: 'No seat for you', hint: 'This server admits players with a seat only.', retry: false },
  flood: { title: 'Disconnected for flooding', hint: 'This page sent more than the server allows.', retry: true },
  'too-many-errors': { title: 'Disconnected after errors', hint: 'The server refused too many messages from this page.', retry: true },
  unreachable: { title: 'Server unreachable', hint: 'The connection dropped and could not be made again.', retry: true },
  'room-moved': { title: 'Cannot reach the room', hint: 'The room kept moving between servers of the fleet: pick it again from the list.', retry: true },
  'bad-request': { title: 'Cannot join', hint: 'Check the room id and the name in the address.', retry: false },
};

/** The message for an ending reason; unknown reasons read as a plain disconnect. */
export function closedMessage(reason: string): ClosedMessage {
  return MESSAGES[reason] ?? { title: 'Disconnected', hint: 'The connection to the server ended.', retry: true };
}
