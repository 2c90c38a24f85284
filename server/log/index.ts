// Public surface of the input log: format types, the file writer, the streaming reader, the in-memory reader.
export { crc32, crc32Update } from './crc32.ts';
export { installedJoltVersion } from './jolt-version.ts';
export { readLogBytes, type LogContents } from './log-bytes.ts';
export { LogEncoder, type LogHeaderInit } from './log-encoder.ts';
export { LOG_FORMAT_VERSION, LogCorruptError, LogFormatError, type LogEntry, type LogHeader, type LogOutcome, type LogStatus } from './log-format.ts';
export { LogReader, type LogReaderOptions } from './log-reader.ts';
export { LogWriter, type LogWriterOptions } from './log-writer.ts';
