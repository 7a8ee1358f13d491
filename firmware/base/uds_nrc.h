/* UDS negative response codes the device answers (ISO 14229-1 values; docs/protocol.md).
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef UDS_NRC_H
#define UDS_NRC_H

#define UDS_NRC_OK 0x00u /* positive response */
#define UDS_NRC_GENERAL_REJECT 0x10u         /* generalReject */
#define UDS_NRC_SERVICE_NOT_SUPPORTED 0x11u  /* serviceNotSupported */
#define UDS_NRC_SUBFUNCTION_NOT_SUPPORTED 0x12u /* subFunctionNotSupported */
#define UDS_NRC_INCORRECT_LENGTH 0x13u       /* incorrectMessageLengthOrInvalidFormat */
#define UDS_NRC_RESPONSE_TOO_LONG 0x14u      /* responseTooLong */
#define UDS_NRC_BUSY_REPEAT_REQUEST 0x21u    /* busyRepeatRequest */
#define UDS_NRC_CONDITIONS_NOT_CORRECT 0x22u /* conditionsNotCorrect */
#define UDS_NRC_REQUEST_SEQUENCE_ERROR 0x24u /* requestSequenceError */
#define UDS_NRC_REQUEST_OUT_OF_RANGE 0x31u   /* requestOutOfRange */
#define UDS_NRC_SECURITY_ACCESS_DENIED 0x33u /* securityAccessDenied */
#define UDS_NRC_INVALID_KEY 0x35u            /* invalidKey */
#define UDS_NRC_EXCEEDED_ATTEMPTS 0x36u      /* exceededNumberOfAttempts */
#define UDS_NRC_DELAY_NOT_EXPIRED 0x37u      /* requiredTimeDelayNotExpired */
#define UDS_NRC_UPLOAD_DOWNLOAD_NOT_ACCEPTED 0x70u /* uploadDownloadNotAccepted */
#define UDS_NRC_TRANSFER_SUSPENDED 0x71u     /* transferDataSuspended */
#define UDS_NRC_PROGRAMMING_FAILURE 0x72u    /* generalProgrammingFailure */
#define UDS_NRC_WRONG_BLOCK_COUNTER 0x73u    /* wrongBlockSequenceCounter */
#define UDS_NRC_RESPONSE_PENDING 0x78u       /* requestCorrectlyReceived-ResponsePending */
#define UDS_NRC_SUBFUNCTION_NOT_IN_SESSION 0x7Eu /* subFunctionNotSupportedInActiveSession */
#define UDS_NRC_SERVICE_NOT_IN_SESSION 0x7Fu /* serviceNotSupportedInActiveSession */
#define UDS_NRC_FW_HEADER 0xF0u              /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_TARGET 0xF1u              /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_TRUNCATED 0xF2u           /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_HASH 0xF3u                /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_TAG 0xF4u                 /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_DOWNGRADE 0xF5u           /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_SKILL_FORMAT 0xF6u        /* vehicleManufacturerSpecific */
#define UDS_NRC_FW_CONFIG_FORMAT 0xF7u       /* vehicleManufacturerSpecific */

#endif /* UDS_NRC_H */
