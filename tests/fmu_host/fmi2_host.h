/* fmi2_host.h -- the importer's view of FMI 2.0, written from the standard
 * (sections 2.1.2-2.1.9, 4.2) for this test: the platform types, the
 * callback struct and one function-pointer type per fmi2 function. It does
 * not include anything of fmu/: the test is an outside master. */
#ifndef RTB_FMU_HOST_FMI2_HOST_H
#define RTB_FMU_HOST_FMI2_HOST_H

#include <stddef.h>

typedef void *fmi2Component;
typedef void *fmi2ComponentEnvironment;
typedef void *fmi2FMUstate;
typedef unsigned int fmi2ValueReference;
typedef double fmi2Real;
typedef int fmi2Integer;
typedef int fmi2Boolean;
typedef char fmi2Char;
typedef const fmi2Char *fmi2String;
typedef char fmi2Byte;
#define fmi2True 1
#define fmi2False 0

typedef enum { fmi2OK, fmi2Warning, fmi2Discard, fmi2Error, fmi2Fatal, fmi2Pending } fmi2Status;
typedef enum { fmi2ModelExchange, fmi2CoSimulation } fmi2Type;
typedef enum { fmi2DoStepStatus, fmi2PendingStatus, fmi2LastSuccessfulTime, fmi2Terminated } fmi2StatusKind;

typedef struct {
  void (*logger)(fmi2ComponentEnvironment, fmi2String, fmi2Status, fmi2String, fmi2String, ...);
  void *(*allocateMemory)(size_t, size_t);
  void (*freeMemory)(void *);
  void (*stepFinished)(fmi2ComponentEnvironment, fmi2Status);
  fmi2ComponentEnvironment componentEnvironment;
} fmi2CallbackFunctions;

typedef struct {
  fmi2Boolean newDiscreteStatesNeeded, terminateSimulation, nominalsOfContinuousStatesChanged,
      valuesOfContinuousStatesChanged, nextEventTimeDefined;
  fmi2Real nextEventTime;
} fmi2EventInfo;

/* Every function of the standard, resolved by dlsym (fmu_load.c). */
typedef struct fmi2_api {
  const char *(*GetTypesPlatform)(void);
  const char *(*GetVersion)(void);
  fmi2Status (*SetDebugLogging)(fmi2Component, fmi2Boolean, size_t, const fmi2String[]);
  fmi2Component (*Instantiate)(fmi2String, fmi2Type, fmi2String, fmi2String,
                               const fmi2CallbackFunctions *, fmi2Boolean, fmi2Boolean);
  void (*FreeInstance)(fmi2Component);
  fmi2Status (*SetupExperiment)(fmi2Component, fmi2Boolean, fmi2Real, fmi2Real, fmi2Boolean, fmi2Real);
  fmi2Status (*EnterInitializationMode)(fmi2Component);
  fmi2Status (*ExitInitializationMode)(fmi2Component);
  fmi2Status (*Terminate)(fmi2Component);
  fmi2Status (*Reset)(fmi2Component);
  fmi2Status (*GetReal)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Real[]);
  fmi2Status (*GetInteger)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Integer[]);
  fmi2Status (*GetBoolean)(fmi2Component, const fmi2ValueReference[], size_t, fmi2Boolean[]);
  fmi2Status (*GetString)(fmi2Component, const fmi2ValueReference[], size_t, fmi2String[]);
  fmi2Status (*SetReal)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Real[]);
  fmi2Status (*SetInteger)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Integer[]);
  fmi2Status (*SetBoolean)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2Boolean[]);
  fmi2Status (*SetString)(fmi2Component, const fmi2ValueReference[], size_t, const fmi2String[]);
  fmi2Status (*GetFMUstate)(fmi2Component, fmi2FMUstate *);
  fmi2Status (*SetFMUstate)(fmi2Component, fmi2FMUstate);
  fmi2Status (*FreeFMUstate)(fmi2Component, fmi2FMUstate *);
  fmi2Status (*SerializedFMUstateSize)(fmi2Component, fmi2FMUstate, size_t *);
  fmi2Status (*SerializeFMUstate)(fmi2Component, fmi2FMUstate, fmi2Byte[], size_t);
  fmi2Status (*DeSerializeFMUstate)(fmi2Component, const fmi2Byte[], size_t, fmi2FMUstate *);
  fmi2Status (*GetDirectionalDerivative)(fmi2Component, const fmi2ValueReference[], size_t,
                                         const fmi2ValueReference[], size_t, const fmi2Real[],
                                         fmi2Real[]);
  /* model exchange */
  fmi2Status (*EnterEventMode)(fmi2Component);
  fmi2Status (*NewDiscreteStates)(fmi2Component, fmi2EventInfo *);
  fmi2Status (*EnterContinuousTimeMode)(fmi2Component);
  fmi2Status (*CompletedIntegratorStep)(fmi2Component, fmi2Boolean, fmi2Boolean *, fmi2Boolean *);
  fmi2Status (*SetTime)(fmi2Component, fmi2Real);
  fmi2Status (*SetContinuousStates)(fmi2Component, const fmi2Real[], size_t);
  fmi2Status (*GetDerivatives)(fmi2Component, fmi2Real[], size_t);
  fmi2Status (*GetEventIndicators)(fmi2Component, fmi2Real[], size_t);
  fmi2Status (*GetContinuousStates)(fmi2Component, fmi2Real[], size_t);
  fmi2Status (*GetNominalsOfContinuousStates)(fmi2Component, fmi2Real[], size_t);
  /* co-simulation */
  fmi2Status (*SetRealInputDerivatives)(fmi2Component, const fmi2ValueReference[], size_t,
                                        const fmi2Integer[], const fmi2Real[]);
  fmi2Status (*GetRealOutputDerivatives)(fmi2Component, const fmi2ValueReference[], size_t,
                                         const fmi2Integer[], fmi2Real[]);
  fmi2Status (*DoStep)(fmi2Component, fmi2Real, fmi2Real, fmi2Boolean);
  fmi2Status (*CancelStep)(fmi2Component);
  fmi2Status (*GetStatus)(fmi2Component, const fmi2StatusKind, fmi2Status *);
  fmi2Status (*GetRealStatus)(fmi2Component, const fmi2StatusKind, fmi2Real *);
  fmi2Status (*GetIntegerStatus)(fmi2Component, const fmi2StatusKind, fmi2Integer *);
  fmi2Status (*GetBooleanStatus)(fmi2Component, const fmi2StatusKind, fmi2Boolean *);
  fmi2Status (*GetStringStatus)(fmi2Component, const fmi2StatusKind, fmi2String *);
} fmi2_api;

#endif /* RTB_FMU_HOST_FMI2_HOST_H */
