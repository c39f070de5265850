#include "vtkKeptStep.h"

#include "vtkDataArray.h"

namespace mmv
{
KeptStepData::KeptStepData(vtkDataArray* scalars, vtkMTimeType time)
  : Scalars(scalars)
  , Time(time)
{
}

bool KeptStepData::Is(vtkDataArray* scalars) const
{
  return scalars && this->Scalars == scalars && scalars->GetMTime() == this->Time;
}

bool KeptStepData::CanReturn() const
{
  return this->Is(this->Scalars);
}

bool KeptStepData::operator==(const KeptStepData& o) const
{
  return this->Scalars == o.Scalars && this->Time == o.Time;
}
}
