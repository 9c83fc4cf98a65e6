#include "vtkSMShockInputArrayInitializationHelper.h"

#include "vtkObjectFactory.h"
#include "vtkPVXMLElement.h"
#include "vtkSMArrayListDomain.h"
#include "vtkSMInputProperty.h"
#include "vtkSMSourceProxy.h"
#include "vtkSMStringVectorProperty.h"

#include <cstdlib>
#include <string>

vtkStandardNewMacro(vtkSMShockInputArrayInitializationHelper);

namespace
{
// Whether the domain offers the array (association, name) of a 5-element
// SetInputArrayToProcess property.
bool Offers(vtkSMArrayListDomain* domain, int association, const std::string& name)
{
  for (unsigned int i = 0; i < domain->GetNumberOfStrings(); ++i)
  {
    if (name == domain->GetString(i) && association == domain->GetFieldAssociation(i))
    {
      return true;
    }
  }
  return false;
}
}

void vtkSMShockInputArrayInitializationHelper::PostInitializeProxy(
  vtkSMProxy* proxy, vtkPVXMLElement* xml, vtkMTimeType vtkNotUsed(initializationTimeStamp))
{
  const char* key = xml ? xml->GetAttributeOrDefault("property", "SelectInputArray") : "SelectInputArray";
  auto* array = vtkSMStringVectorProperty::SafeDownCast(proxy->GetProperty(key));
  auto* inputProperty = vtkSMInputProperty::SafeDownCast(proxy->GetProperty("Input"));
  if (!array || array->GetNumberOfElements() != 5 || !inputProperty ||
    inputProperty->GetNumberOfProxies() == 0)
  {
    return;
  }
  auto* input = vtkSMSourceProxy::SafeDownCast(inputProperty->GetProxy(0));
  auto* domain = array->FindDomain<vtkSMArrayListDomain>();
  if (!input || !domain)
  {
    return;
  }
  const std::string name = array->GetElement(4) ? array->GetElement(4) : "";
  const int association = array->GetElement(3) ? std::atoi(array->GetElement(3)) : -1;
  const bool chosenAfterInput = array->GetMTime() > inputProperty->GetMTime();
  if (!name.empty() && chosenAfterInput)
  {
    return;
  }
  // The domain lists the arrays of the input's data information, which is
  // empty until the input has run.
  input->UpdatePipeline();
  domain->Update(nullptr);
  if (name.empty() || !Offers(domain, association, name))
  {
    array->ResetToDomainDefaults();
  }
}

void vtkSMShockInputArrayInitializationHelper::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
